#!/usr/bin/env python3
"""Mitsuba 3's white-furnace values for mcrt-render/tests/it/furnace.rs: a unit sphere of each material
under a constant environment of radiance 1, seen by a narrow camera (fov 8 degrees from
z = 5, 32x32 pixels, box filter) so that every pixel sees the sphere; prints the image mean
and its standard error (from the spread of independent passes).

Usage:  python3 scripts/mitsuba_furnace.py [--spp 16384]
Needs the packages of scripts/requirements.txt and libLLVM (see scripts/README.md).
"""

from __future__ import annotations

import argparse

from contenders import check_variant, import_mitsuba

MATERIALS = {
    "roughdielectric ggx 0.3": {"type": "roughdielectric", "distribution": "ggx",
                                "alpha": 0.3, "int_ior": 1.5, "ext_ior": 1.0},
    "roughdielectric ggx 0.01": {"type": "roughdielectric", "distribution": "ggx",
                                 "alpha": 0.01, "int_ior": 1.5, "ext_ior": 1.0},
    "plastic white": {"type": "plastic", "diffuse_reflectance": {"type": "rgb", "value": 1.0}},
    "roughplastic white": {"type": "roughplastic",
                           "diffuse_reflectance": {"type": "rgb", "value": 1.0}},
    "roughplastic white ggx 0.3": {"type": "roughplastic", "distribution": "ggx", "alpha": 0.3,
                                   "diffuse_reflectance": {"type": "rgb", "value": 1.0}},
    "thindielectric": {"type": "thindielectric", "int_ior": 1.5, "ext_ior": 1.0},
    "principled white": {"type": "principled", "base_color": {"type": "rgb", "value": 1.0}},
    "principled white metal aniso": {"type": "principled", "metallic": 1.0, "roughness": 0.4,
                                     "anisotropic": 0.8,
                                     "base_color": {"type": "rgb", "value": 1.0}},
    "principled white spec_trans": {"type": "principled", "spec_trans": 0.8, "roughness": 0.3,
                                    "base_color": {"type": "rgb", "value": 1.0}},
}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--spp", type=int, default=16384)
    ap.add_argument("--passes", type=int, default=16)
    ap.add_argument("--only", default="", help="render only materials whose name has this")
    a = ap.parse_args()
    mi, _ = import_mitsuba(["llvm_ad_rgb"])
    check_variant(mi, "llvm_ad_rgb")
    import numpy as np

    for name, bsdf in MATERIALS.items():
        if a.only not in name:
            continue
        scene = mi.load_dict({
            "type": "scene",
            "integrator": {"type": "path", "max_depth": -1},
            "sensor": {
                "type": "perspective", "fov": 8,
                "to_world": mi.ScalarTransform4f().look_at(
                    origin=[0, 0, 5], target=[0, 0, 0], up=[0, 1, 0]),
                "film": {"type": "hdrfilm", "width": 32, "height": 32,
                         "rfilter": {"type": "box"}},
            },
            "sphere": {"type": "sphere", "bsdf": bsdf},
            "env": {"type": "constant", "radiance": {"type": "rgb", "value": 1.0}},
        })
        per = a.spp // a.passes
        means = [np.array(mi.render(scene, spp=per, seed=i))[:, :, :3].mean()
                 for i in range(a.passes)]
        m, se = float(np.mean(means)), float(np.std(means, ddof=1) / np.sqrt(a.passes))
        print(f"{name:28s} {m:.5f} +- {se:.5f}  ({a.spp} spp)")


if __name__ == "__main__":
    main()
