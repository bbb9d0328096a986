#!/usr/bin/env python3
"""Write the 64x64 PNG textures of mcrt-render/tests/data/published/maps/ (issue 25):
`domes.png`, a tangent-space normal map of a 4x4 grid of round domes (RGB, n -> (n + 1)/2,
8-bit, meant to be read with raw=true); `ripples.png`, a grey height field
0.5 + 0.5 sin(2 pi 3 x) sin(2 pi 2 y) (8-bit); `alpha.png`, a grey roughness map of
four bands along v from 0.02 to 0.6, each with a gentle ramp along u (8-bit).

Usage: python3 scripts/make_map_textures.py [OUT_DIR]
"""

import sys
from pathlib import Path

import numpy as np
import mitsuba as mi

mi.set_variant("scalar_rgb")
out = Path(sys.argv[1] if len(sys.argv) > 1 else "mcrt-render/tests/data/published/maps")
n = 64
# Pixel centres in [0, 1): x along u (columns), y along v (rows, row 0 = v near 0).
x = (np.arange(n) + 0.5) / n
X, Y = np.meshgrid(x, x)


def u8(a):
    return np.clip(np.round(a * 255.0), 0, 255).astype(np.uint8)


# Domes: in each of 4 x 4 cells a spherical cap of radius 0.4 cells; flat outside.
cx, cy = (X * 4) % 1.0 - 0.5, (Y * 4) % 1.0 - 0.5
r2 = cx * cx + cy * cy
R = 0.4
inside = r2 < R * R
h = np.sqrt(np.maximum(R * R - r2, 1e-6))
nx = np.where(inside, cx / h, 0.0) * 0.7
ny = np.where(inside, cy / h, 0.0) * 0.7
nz = np.ones_like(nx)
norm = np.sqrt(nx * nx + ny * ny + nz * nz)
normals = np.stack([nx / norm, ny / norm, nz / norm], axis=-1)
mi.Bitmap(u8((normals + 1.0) / 2.0)).write(str(out / "domes.png"))

ripples = 0.5 + 0.5 * np.sin(2 * np.pi * 3 * X) * np.sin(2 * np.pi * 2 * Y)
mi.Bitmap(u8(ripples)[:, :, None]).write(str(out / "ripples.png"))

band = np.floor(Y * 4) / 3.0  # 0, 1/3, 2/3, 1 across the four bands (along v)
ramp = (X - 0.5) * 0.2
alpha = 0.02 + 0.58 * np.clip(band + ramp * band, 0.0, 1.0)
mi.Bitmap(u8(alpha)[:, :, None]).write(str(out / "alpha.png"))
print("wrote", out / "domes.png", out / "ripples.png", out / "alpha.png")
