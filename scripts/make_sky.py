#!/usr/bin/env python3
"""Write mcrt-render/tests/data/sky.exr: a small synthetic latitude-longitude environment map (64 x 32,
linear RGB float32) for the rotated-envmap reference scene: a blue-to-white sky over a dark
brown ground, with a warm sun disk of about 10 degrees radius at azimuth u = 0.3, elevation
35 degrees, so that a rotation of the map is plain in the render (shadows, colours).

Usage: python3 scripts/make_sky.py [--out mcrt-render/tests/data/sky.exr]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from contenders import import_mitsuba


def sky(width: int = 64, height: int = 32):
    import numpy as np

    img = np.zeros((height, width, 3), dtype=np.float32)
    sun_u, sun_elev = 0.3, math.radians(35.0)
    # The map's direction convention (Mitsuba 3): (sin t sin p, cos t, -sin t cos p).
    st, ct = math.cos(sun_elev), math.sin(sun_elev)
    sp, cp = math.sin(2 * math.pi * sun_u), math.cos(2 * math.pi * sun_u)
    sun = np.array([st * sp, ct, -st * cp])
    for y in range(height):
        theta = math.pi * (y + 0.5) / height
        for x in range(width):
            phi = 2 * math.pi * (x + 0.5) / width
            d = np.array([math.sin(theta) * math.sin(phi), math.cos(theta),
                          -math.sin(theta) * math.cos(phi)])
            if d[1] > 0:
                t = d[1]
                c = (1 - t) * np.array([0.9, 0.9, 1.0]) + t * np.array([0.25, 0.45, 1.0])
            else:
                c = np.array([0.12, 0.08, 0.05])
            if math.degrees(math.acos(min(1.0, float(d @ sun)))) < 10.0:
                c = np.array([30.0, 24.0, 16.0])
            img[y, x] = c
    return img


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", type=Path, default=Path("mcrt-render/tests/data/sky.exr"))
    a = ap.parse_args()
    mi, _ = import_mitsuba(["scalar_rgb"])
    mi.Bitmap(sky()).write(str(a.out))
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
