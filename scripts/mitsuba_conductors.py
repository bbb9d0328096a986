#!/usr/bin/env python3
"""Print the RGB complex indices of refraction that Mitsuba 3's RGB variants use for the
named conductor materials (`<string name="material" value="Au"/>`), as the Rust table of
`mcrt-render/src/bsdf/named_conductors.rs`.

Mitsuba 3 ships each material as two tabulated spectra (`data/ior/<name>.eta.spd` and
`<name>.k.spd`, measured optical constants from the LuxPop database, which compiles Palik,
"Handbook of Optical Constants of Solids", 1985-1998). Its RGB variants reduce each spectrum
to linear sRGB once, when the plugin loads; this script asks Mitsuba for the result (it
loads every material and reads `eta` and `k` with `mi.traverse`) and, with `--check`, also
recomputes it independently from the `.spd` files:

  1. 1000 wavelengths evenly spaced on [360, 830] nm; at each, the spectrum interpolated
     linearly (zero outside its tabulated range) times the CIE 1931 2-degree colour
     matching functions;
  2. the sum divided by the same sum over y-bar (so a constant spectrum c gives Y = c);
  3. XYZ to linear sRGB (Rec. 709 primaries, D65 white), negative channels clamped to 0.

Usage:  python3 scripts/mitsuba_conductors.py [--check] > table.txt
(Needs the packages of scripts/requirements.txt; the scalar_rgb variant suffices.)
"""

from __future__ import annotations

import argparse
import os
import sys

import numpy as np


def spd(path: str) -> tuple[np.ndarray, np.ndarray]:
    rows = [
        [float(x) for x in line.split()]
        for line in open(path, encoding="ascii")
        if line.strip() and not line.lstrip().startswith("#")
    ]
    a = np.array(rows)
    return a[:, 0], a[:, 1]


XYZ_TO_SRGB = np.array(
    [
        [3.240479, -1.537150, -0.498535],
        [-0.969256, 1.875991, 0.041556],
        [0.055648, -0.204043, 1.057311],
    ]
)


def reduce_to_rgb(mi, wavelengths: np.ndarray, values: np.ndarray) -> np.ndarray:
    xs = np.linspace(360.0, 830.0, 1000)
    cmf = np.array([list(mi.cie1931_xyz(float(x))) for x in xs])
    inside = (xs >= wavelengths[0]) & (xs <= wavelengths[-1])
    v = np.where(inside, np.interp(xs, wavelengths, values), 0.0)
    xyz = (cmf * v[:, None]).sum(axis=0) / cmf[:, 1].sum()
    return np.maximum(XYZ_TO_SRGB @ xyz, 0.0)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--check", action="store_true",
                    help="recompute every value from the .spd files and compare")
    a = ap.parse_args()
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    mi.set_log_level(mi.LogLevel.Error)
    folder = os.path.join(os.path.dirname(mi.__file__), "data", "ior")
    names = sorted({f.split(".")[0] for f in os.listdir(folder) if f.endswith(".eta.spd")})
    worst = 0.0
    for name in names:
        params = mi.traverse(mi.load_dict({"type": "conductor", "material": name}))
        eta = np.array(params["eta.value"], dtype=np.float32)
        k = np.array(params["k.value"], dtype=np.float32)
        if a.check:
            for part, got in (("eta", eta), ("k", k)):
                want = reduce_to_rgb(mi, *spd(os.path.join(folder, f"{name}.{part}.spd")))
                err = float(np.max(np.abs(want - got) / np.maximum(np.abs(want), 1e-3)))
                worst = max(worst, err)
                if err > 1e-5:
                    print(f"{name}.{part}: mitsuba {got}, recomputed {want}", file=sys.stderr)
        fmt = lambda v: ", ".join(str(np.float32(x)) for x in v)  # noqa: E731
        print(f'    ("{name}", [{fmt(eta)}], [{fmt(k)}]),')
    if a.check:
        print(f"{len(names)} materials; worst relative difference {worst:.2e}", file=sys.stderr)


if __name__ == "__main__":
    main()
