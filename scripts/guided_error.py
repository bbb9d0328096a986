#!/usr/bin/env python3
"""Error per sample of the guided path tracer against the path tracer (no timing).

relMSE = mean((img - ref)^2 / (ref^2 + 0.01)) against the reference EXR beside each scene,
for each integrator and seed, at fixed spp; the mean over the seeds is printed. Error at
fixed samples is deterministic given the seeds, so the figures do not depend on the load.

    python3 scripts/guided_error.py mcrt-render/tests/data/issue28/indirect.xml \\
        --spp 64 --seeds 1 2 3 --sampler sobol --integrators path guided

With --pairs (for a scene without a reference, such as the study scene indirect-deep.xml of
`make_issue28_scenes.py --shade-height 0.5`), the seeds are taken in pairs and each pair's
half squared difference estimates the variance, so the printed figure estimates the relMSE
against an exact image: mean((a - b)^2 / 2 / (m^2 + 0.01)), m the mean of the integrator's
images over all seeds (the estimators are unbiased, so the difference holds no bias).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from compare_mitsuba import reference_for, relmse  # noqa: E402
from contenders import REPO, read_exr  # noqa: E402


def pair_variances(images: list) -> list[float]:
    """Per pair of images (0 and 1, 2 and 3, ...) of an unbiased estimator, the estimate of
    the relMSE against an exact image: mean((a - b)^2 / 2 / (m^2 + 0.01))."""
    m = sum(images) / len(images)
    den = m * m + 0.01
    return [float((((images[i] - images[i + 1]) ** 2) / 2.0 / den).mean())
            for i in range(0, len(images), 2)]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--spp", type=int, nargs="+", default=[64])
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--sampler", default=None, help="--sampler of render (default: the scene's)")
    ap.add_argument("--integrators", nargs="+", default=["path", "guided"])
    ap.add_argument("--bin", default=str(REPO / "target/release/render"))
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--pairs", action="store_true",
                    help="no reference: the variance from pairs of seeds (an even number)")
    a = ap.parse_args()
    if a.pairs and len(a.seeds) % 2:
        ap.error("--pairs needs an even number of seeds")
    with tempfile.TemporaryDirectory() as tmp:
        for scene in a.scenes:
            if a.pairs:
                scene_path, ref = Path(scene), None
            else:
                scene_path, ref_path = reference_for(scene, {})
                ref = read_exr(ref_path)
            for spp in a.spp:
                for integ in a.integrators:
                    errs, images = [], []
                    for seed in a.seeds:
                        out = Path(tmp) / f"{integ}-{seed}.exr"
                        cmd = [a.bin, str(scene_path), "--integrator", integ, "--spp", str(spp),
                               "--seed", str(seed), "--threads", str(a.threads), "-o", str(out)]
                        if a.sampler:
                            cmd += ["--sampler", a.sampler]
                        subprocess.run(cmd, check=True, capture_output=True)
                        if a.pairs:
                            images.append(read_exr(out))
                        else:
                            errs.append(relmse(read_exr(out), ref))
                    if a.pairs:
                        errs = pair_variances(images)
                    mean = sum(errs) / len(errs)
                    each = " / ".join(f"{e:.5f}" for e in errs)
                    print(f"{scene_path.name} spp {spp} sampler {a.sampler or 'scene'} "
                          f"{integ}: relMSE {mean:.5f} ({each})", flush=True)


if __name__ == "__main__":
    main()
