#!/usr/bin/env python3
"""Error per sample of our samplers and Mitsuba 3's, averaged over seeds (no timing).

relMSE = mean((img - ref)^2 / (ref^2 + 0.01)) against each scene's reference, for every
(scene, spp, sampler), over seeds 1..--seeds; the table gives the mean, its standard error
over the seeds, and the ratio to the best Mitsuba sampler's mean. Error per sample is
deterministic given the seeds, so the figures do not depend on the machine's load.

Results are cached in --cache (JSON), keyed by (scene, spp, seed, contender label), so a
rerun only renders what is missing; --tag names our renderer's build in the label (change
it when the code changes, or pass --fresh).

    python3 scripts/sampler_error.py mcrt-render/tests/data/veach-mis.xml --spp 64 256 --seeds 8 \\
        --samplers sobol sobol4d cmj --mitsuba-samplers ldsampler multijitter \\
        --markdown out/samplers.md
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from compare_mitsuba import reference_for, relmse  # noqa: E402
from contenders import (REPO, MitsubaContender, OursContender, Skip,  # noqa: E402
                        build_renderer, import_mitsuba, read_exr)


def split_list(items: list[str]) -> list[str]:
    """Names given with spaces or commas."""
    return [x for item in items for x in item.split(",") if x]


def mean_and_se(xs: list[float]) -> tuple[float, float]:
    """Mean and standard error of the mean (0 for a single value)."""
    m = sum(xs) / len(xs)
    if len(xs) < 2:
        return m, 0.0
    var = sum((x - m) ** 2 for x in xs) / (len(xs) - 1)
    return m, math.sqrt(var / len(xs))


def save(path: Path, cache: dict) -> None:
    """Write the cache, merged with what other runs sharing the file wrote meanwhile."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if path.exists():
        for k, v in json.loads(path.read_text()).items():
            cache.setdefault(k, v)
    tmp = path.with_suffix(f".{os.getpid()}.tmp")
    tmp.write_text(json.dumps(cache, indent=0, sort_keys=True))
    tmp.replace(path)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("scenes", nargs="*", default=[
        "mcrt-render/tests/data/cornell-box.xml", "mcrt-render/tests/data/veach-mis.xml",
        "mcrt-render/tests/data/cornell-box-caustic.xml"])
    p.add_argument("--spp", type=int, nargs="+", default=[64, 256])
    p.add_argument("--seeds", type=int, default=8, help="seeds 1..N per configuration")
    p.add_argument("--samplers", nargs="+", default=["independent", "sobol"],
                   help="our samplers (spaces or commas)")
    p.add_argument("--ours-args", nargs="+", default=[""],
                   help="extra arguments for our renderer, one configuration each")
    p.add_argument("--mitsuba-samplers", nargs="+",
                   default=["independent", "ldsampler", "multijitter"])
    p.add_argument("--variant", default="llvm_ad_rgb")
    p.add_argument("--tag", default="", help="names our build in the cache keys")
    p.add_argument("--cache", default="out/sampler_error.json")
    p.add_argument("--fresh", action="store_true", help="ignore cached results")
    p.add_argument("--no-build", action="store_true")
    p.add_argument("--renderer", type=Path, default=REPO / "target/release/render",
                   help="our render binary (a copy keeps a run independent of rebuilds)")
    p.add_argument("--skip-mitsuba", action="store_true")
    p.add_argument("--threads", type=int, default=0)
    p.add_argument("--markdown", help="also write the table here")
    a = p.parse_args()

    samplers = split_list(a.samplers)
    mi_samplers = [] if a.skip_mitsuba else split_list(a.mitsuba_samplers)
    binary = a.renderer
    if not a.no_build:
        build_renderer(binary)
    mi, dr = import_mitsuba([a.variant])
    cache_path = Path(a.cache)
    cache = {} if a.fresh or not cache_path.exists() else json.loads(cache_path.read_text())
    tmp = tempfile.mkdtemp(prefix="sampler_error-")
    tag = f"[{a.tag}]" if a.tag else ""

    rows = []
    for scene in a.scenes:
        scene_path, ref_path = reference_for(scene, {})
        ref = read_exr(ref_path)
        contenders = [(f"mitsuba {s}", MitsubaContender(mi, dr, a.variant, {}, s))
                      for s in mi_samplers]
        for extra in a.ours_args:
            for s in samplers:
                c = OursContender(binary, s, extra, {}, a.threads, tmp)
                contenders.append((f"mcrt{tag} {c.name[4:].strip()} {c.sampler}".replace(
                    "  ", " "), c))
        ready = set()
        for spp in a.spp:
            for label, c in contenders:
                keys = [f"{scene_path.stem}|{spp}|{seed}|{label}"
                        for seed in range(1, a.seeds + 1)]
                if any(k not in cache for k in keys) and label not in ready:
                    try:
                        c.setup(scene_path)
                        ready.add(label)
                    except Skip as e:
                        print(f"skipping {e}", file=sys.stderr)
                        continue
                for seed, k in zip(range(1, a.seeds + 1), keys):
                    if k not in cache:
                        cache[k] = relmse(c.render(spp, seed).img, ref)
                        save(cache_path, cache)
                values = sorted(cache[k] for k in keys)
                m, se = mean_and_se(values)
                h = len(values) // 2
                med = values[h] if len(values) % 2 else (values[h - 1] + values[h]) / 2
                rows.append((scene_path.stem, spp, label, m, se, med))
                print(f"{scene_path.stem} {spp} {label}: {m:.4g} ± {se:.2g}", file=sys.stderr)

    best = {}
    for scene, spp, label, m, *_ in rows:
        if label.startswith("mitsuba"):
            best[(scene, spp)] = min(best.get((scene, spp), math.inf), m)
    lines = [f"relMSE, mean ± standard error and median over seeds 1..{a.seeds}; ratio of "
             "the means to the best Mitsuba sampler's (below 1: ours is better)", "",
             "| scene | spp | renderer and sampler | relMSE | ± | median | ÷ best Mitsuba |",
             "|---|---|---|---|---|---|---|"]
    for scene, spp, label, m, se, med in rows:
        ratio = m / best[(scene, spp)] if (scene, spp) in best else math.nan
        lines.append(f"| {scene} | {spp} | {label} | {m:.3g} | {se:.2g} | {med:.3g} | "
                     f"{ratio:.3g} |")
    text = "\n".join(lines)
    print(text)
    if a.markdown:
        Path(a.markdown).parent.mkdir(parents=True, exist_ok=True)
        Path(a.markdown).write_text(text + "\n")


if __name__ == "__main__":
    main()
