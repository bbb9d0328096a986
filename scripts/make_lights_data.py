#!/usr/bin/env python3
"""Write the images of mcrt-render/tests/data/published/lights/ (issue 25): a Radiance RGBE
environment map and texture (`sky.hdr`, `tiles.hdr`) and an 8-bit PNG slide (`slide.png`)
for the textured spot and the projector. Mitsuba 3.9.1 writes them, so that its own reader
and writer define the files.

Usage: python3 scripts/make_lights_data.py
"""

from pathlib import Path

import numpy as np
from contenders import import_mitsuba

OUT = Path(__file__).resolve().parent.parent / "mcrt-render/tests/data/published/lights"


def main() -> None:
    mi, _ = import_mitsuba(["scalar_rgb"])
    h, w = 32, 64
    v, u = np.meshgrid((np.arange(h) + 0.5) / h, (np.arange(w) + 0.5) / w, indexing="ij")
    sky = np.stack([0.3 + 0.5 * v, 0.4 + 0.3 * v, 0.9 - 0.5 * v], axis=-1)
    sky *= (1.0 + 0.5 * np.cos(2 * np.pi * u))[..., None]
    sky[4:8, 40:46] = [40.0, 32.0, 20.0]  # a sun
    mi.Bitmap(sky.astype(np.float32)).write(str(OUT / "sky.hdr"))
    n = 16
    y, x = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    tiles = np.where(((x // 4 + y // 4) % 2 == 0)[..., None], [0.8, 0.6, 0.2], [0.1, 0.3, 0.7])
    tiles = tiles * (0.5 + x / n)[..., None]
    mi.Bitmap(tiles.astype(np.float32)).write(str(OUT / "tiles.hdr"))
    sy, sx = np.meshgrid(np.arange(24), np.arange(32), indexing="ij")
    slide = np.zeros((24, 32, 3), dtype=np.uint8)
    slide[..., 0] = 40 + 6 * sx
    slide[..., 1] = np.where((sx // 8 + sy // 8) % 2 == 0, 230, 30)
    slide[..., 2] = 40 + 8 * sy
    slide[2:6, 2:10] = [255, 255, 255]  # a bright mark in the top-left corner
    mi.Bitmap(slide, pixel_format=mi.Bitmap.PixelFormat.RGB).write(str(OUT / "slide.png"))
    for f in ("sky.hdr", "tiles.hdr", "slide.png"):
        print(OUT / f, (OUT / f).stat().st_size, "bytes")


if __name__ == "__main__":
    main()
