#!/usr/bin/env python3
"""Write the texture images of mcrt-render/tests/data/textures/ (used by mcrt-render/tests/data/textures.xml) and
print what Mitsuba 3 makes of them, the facts mcrt-render/src/texture/ was checked against.

Usage:
    python3 scripts/make_texture_data.py            # write the images
    python3 scripts/make_texture_data.py --probe    # also print Mitsuba's lookups

The images are small patterns (no photographs): `grid.png` 16x16 8-bit sRGB, `rings.jpg`
32x32 (JPEG, quality 95), `tiles.exr` 8x8 float. Needs numpy and, with --probe or for
the JPEG, the `mitsuba` package (variant scalar_rgb).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

OUT = Path(__file__).resolve().parent.parent / "mcrt-render" / "tests" / "data" / "textures"


def grid() -> np.ndarray:
    """16x16: a red-to-blue gradient across, a green ramp down, a white cross."""
    y, x = np.mgrid[0:16, 0:16]
    img = np.zeros((16, 16, 3))
    img[..., 0] = 0.9 * (1 - x / 15)
    img[..., 1] = 0.8 * y / 15
    img[..., 2] = 0.9 * x / 15
    img[(x == 7) | (y == 7)] = 0.95
    return (img * 255 + 0.5).astype(np.uint8)


def rings() -> np.ndarray:
    """32x32: concentric orange and teal rings."""
    y, x = np.mgrid[0:32, 0:32]
    r = np.hypot(x - 15.5, y - 15.5)
    band = (r // 4).astype(int) % 2 == 0
    img = np.where(band[..., None], [230, 140, 40], [30, 150, 160])
    return img.astype(np.uint8)


def tiles() -> np.ndarray:
    """8x8 float: a 2x2-pixel tile pattern in three colours, linear values in [0.05, 0.85]."""
    y, x = np.mgrid[0:8, 0:8]
    k = (x // 2 + 2 * (y // 2)) % 3
    colours = np.array([[0.85, 0.3, 0.05], [0.1, 0.6, 0.2], [0.3, 0.3, 0.8]], dtype=np.float32)
    return colours[k]


def probe(mi) -> None:
    """Mitsuba's lookups that the unit tests pin (mcrt-render/src/texture/)."""
    def ev(tex, uv):
        si = mi.SurfaceInteraction3f()
        si.uv = mi.Point2f(*uv)
        return tex.eval(si)

    img = np.array([[[255, 0, 0], [0, 255, 0]], [[0, 0, 255], [128, 128, 128]]], dtype=np.uint8)
    mi.Bitmap(img).write("/tmp/probe.png")
    for props in [{}, {"filter_type": "nearest"}, {"raw": True}, {"wrap_mode": "clamp"},
                  {"wrap_mode": "mirror"}]:
        t = mi.load_dict(dict(type="bitmap", filename="/tmp/probe.png", **props))
        for uv in [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.5, 0.5), (0.0, 0.0),
                   (1.1, 0.25), (-0.1, 0.25), (1.6, 0.75), (0.4, 0.25)]:
            print("bitmap", props, uv, ev(t, uv))
    c = mi.load_dict({"type": "checkerboard"})
    for uv in [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75), (1.25, 0.25)]:
        print("checkerboard", uv, ev(c, uv))
    for shape, o, d in [("rectangle", (0.5, -0.5, 1), (0, 0, -1)),
                        ("disk", (0.5, 0.5, 1), (0, 0, -1)),
                        ("sphere", (-5, 0, 0.3), (1, 0, 0)),
                        ("cube", (0.5, 5, 0.2), (0, -1, 0))]:
        s = mi.load_dict({"type": "scene", "s": {"type": shape}})
        si = s.ray_intersect(mi.Ray3f(o, d))
        print("uv", shape, o, si.uv)
    cube = mi.load_dict({"type": "cube"})
    print("cube texcoords", np.array(cube.vertex_texcoords_buffer()).reshape(-1, 2).tolist())


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--probe", action="store_true")
    a = ap.parse_args()
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    OUT.mkdir(parents=True, exist_ok=True)
    mi.Bitmap(grid()).write(str(OUT / "grid.png"))
    mi.Bitmap(rings()).write(str(OUT / "rings.jpg"), quality=95)
    mi.Bitmap(tiles()).write(str(OUT / "tiles.exr"))
    for f in sorted(OUT.iterdir()):
        print(f, f.stat().st_size, "bytes")
    if a.probe:
        probe(mi)


if __name__ == "__main__":
    main()
