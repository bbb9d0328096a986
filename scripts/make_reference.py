#!/usr/bin/env python3
"""Render a Mitsuba 3 reference image for mcrt-render/tests/data, the way mcrt-render/tests/data/REFERENCES.md
describes: the mean of independent passes `mi.render(scene, spp=PASS, seed=i)`, i = 0, 1, ...,
written as linear RGB float32 EXR. Prints the image mean and the render time.

Usage:
    python3 scripts/make_reference.py mcrt-render/tests/data/cornell-box-glass.xml --spp 4096
    python3 scripts/make_reference.py mcrt-render/tests/data/cornell-box.xml -D max_depth=2 \\
        --spp 4096 --out mcrt-render/tests/data/cornell-box-direct.exr

The output defaults to the scene's path with `.exr`. `-D NAME=VALUE` sets a scene
parameter (repeatable). Needs the packages of scripts/requirements.txt and, for the
default variant llvm_ad_rgb, libLLVM (see scripts/README.md).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from contenders import check_variant, import_mitsuba


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene", type=Path)
    ap.add_argument("--spp", type=int, default=4096, help="total samples per pixel")
    ap.add_argument("--pass-spp", type=int, default=256, help="samples per pixel per pass")
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("-D", dest="defines", action="append", default=[], metavar="NAME=VALUE")
    ap.add_argument("--out", type=Path)
    ap.add_argument("--variance", action="store_true",
                    help="also write OUT-variance.exr: the variance of each pixel's mean, "
                         "estimated from the spread of the passes (for a block test whose "
                         "reference's noise is not ours scaled)")
    ap.add_argument("--all-channels", action="store_true",
                    help="keep every channel of the film (AOVs such as the moment "
                         "integrator's), named as Mitsuba names them")
    a = ap.parse_args()
    if a.spp % a.pass_spp:
        ap.error("--spp must be a multiple of --pass-spp")
    mi, _ = import_mitsuba([a.variant])
    check_variant(mi, a.variant)
    import numpy as np

    params = dict(d.split("=", 1) for d in a.defines)
    scene = mi.load_file(str(a.scene), **params)
    passes = a.spp // a.pass_spp
    acc = None
    acc2 = None
    start = time.perf_counter()
    for i in range(passes):
        img = np.array(mi.render(scene, spp=a.pass_spp, seed=i), dtype=np.float64)
        acc = img if acc is None else acc + img
        if a.variance:
            acc2 = img * img if acc2 is None else acc2 + img * img
    seconds = time.perf_counter() - start
    mean = (acc / passes).astype(np.float32)
    out = a.out or a.scene.with_suffix(".exr")
    if a.all_channels:
        names = [f.name for f in scene.sensors()[0].film().bitmap().struct_()]
        mi.Bitmap(mean, mi.Bitmap.PixelFormat.MultiChannel, names).write(str(out))
    else:
        mean = mean[:, :, :3]
        mi.Bitmap(mean).write(str(out))
    if a.variance:
        if passes < 2:
            ap.error("--variance needs at least two passes")
        m1 = acc[:, :, :3] / passes
        spread = np.maximum(acc2[:, :, :3] / passes - m1 * m1, 0.0) * passes / (passes - 1)
        var_out = out.with_name(out.stem + "-variance.exr")
        mi.Bitmap((spread / passes).astype(np.float32)).write(str(var_out))
    h, w = mean.shape[:2]
    m = mean[:, :, :3].reshape(-1, 3).mean(axis=0)
    print(f"{out}: {w}x{h}, {a.spp} spp in {passes} passes, {seconds:.1f} s "
          f"({w * h * a.spp / seconds / 1e6:.2f} M samples/s); "
          f"mean {m[0]:.5f}, {m[1]:.5f}, {m[2]:.5f}")


if __name__ == "__main__":
    main()
