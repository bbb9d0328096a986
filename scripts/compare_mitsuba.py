#!/usr/bin/env python3
"""Render scenes with Mitsuba 3 and with mcrt side by side, and compare speed and error.

For every scene, sample count and renderer (Mitsuba's `scalar_rgb` and `llvm_ad_rgb`
variants, each with the samplers `independent`, `ldsampler` and `multijitter`, and mcrt's
`render` example with each requested configuration and sampler) the script measures

* the render time, without scene loading and without Mitsuba's JIT compilation: a warm-up
  render comes first and its time is reported separately;
* samples per second (spp x width x height / render time);
* relMSE against the reference image,
  mean((img - ref)^2 / (ref^2 + 0.01)) over all pixels and channels;
* efficiency = 1 / (relMSE x render time), and its ratio to the most efficient Mitsuba
  contender (variant and sampler) at the same scene and sample count.

Each configuration is rendered `--repeats` times with different seeds; the table shows the
mean render time, the mean relMSE and the efficiency computed from those two means.

Requirements: see scripts/README.md (`pip install -r scripts/requirements.txt`).
Example:

    python3 scripts/compare_mitsuba.py --quick
    python3 scripts/compare_mitsuba.py --json out/peer.json --markdown out/peer.md
    python3 scripts/compare_mitsuba.py mcrt-render/tests/data/cornell-box-caustic.xml --no-build \
        --variants llvm_ad_rgb --samplers independent \
        --ours-args "" "--integrator bdpt" "--integrator bdpt --sampler sobol"
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
from dataclasses import asdict, dataclass, field
from pathlib import Path

from contenders import (
    REPO,
    MitsubaContender,
    OursContender,
    Skip,
    build_renderer,
    fail,
    import_mitsuba,
    read_exr,
)

DEFAULT_SCENES = ["mcrt-render/tests/data/cornell-box.xml", "mcrt-render/tests/data/veach-mis.xml"]
DEFAULT_BINARY = "target/release/render"
MITSUBA_VARIANTS = ["scalar_rgb", "llvm_ad_rgb"]
MITSUBA_SAMPLERS = ["independent", "ldsampler", "multijitter"]
# The ratio columns divide by the most efficient result whose "renderer sampler" starts with
# this (at the same scene and spp): by default the best of all Mitsuba variants and samplers.
BASELINE = "mitsuba"


@dataclass
class Result:
    """One configuration (scene, renderer, sampler, spp) measured over several seeds."""

    scene: str
    renderer: str
    sampler: str
    spp: int
    pixels: int
    setup_s: float = float("nan")
    warmup_s: float = float("nan")
    render_s: list[float] = field(default_factory=list)
    wall_s: list[float] = field(default_factory=list)
    cpu_s: list[float] = field(default_factory=list)
    relmse: list[float] = field(default_factory=list)
    note: str = ""

    def mean_time(self) -> float:
        """Mean render time over the repeats, in seconds."""
        return mean(self.render_s)

    def samples_per_s(self) -> float:
        """Samples (camera paths) per second at the mean render time."""
        return self.spp * self.pixels / self.mean_time()

    def mean_relmse(self) -> float:
        """Mean relMSE over the repeats."""
        return mean(self.relmse)

    def efficiency(self) -> float:
        """1 / (relMSE x time), from the means over the repeats."""
        return 1.0 / (self.mean_relmse() * self.mean_time())

    def cpu_efficiency(self) -> float:
        """1 / (relMSE x CPU time): less sensitive to other processes on the machine."""
        return 1.0 / (self.mean_relmse() * mean(self.cpu_s))

    def label(self) -> str:
        """'renderer sampler', e.g. 'mitsuba llvm_ad_rgb ldsampler'."""
        return f"{self.renderer} {self.sampler}"


def best_of(results: list[Result], prefix: str) -> dict[tuple[str, int], Result]:
    """Per (scene, spp), the most efficient result whose label starts with `prefix`."""
    best: dict[tuple[str, int], Result] = {}
    for r in results:
        eff = r.efficiency()
        if not r.label().startswith(prefix) or eff != eff:
            continue
        k = (r.scene, r.spp)
        if k not in best or eff > best[k].efficiency():
            best[k] = r
    return best


def mean(xs: list[float]) -> float:
    """Arithmetic mean; NaN for an empty list."""
    return sum(xs) / len(xs) if xs else float("nan")



def measure_scene(contenders, scene_path, ref, spps, seeds) -> list[Result]:
    """Measure every contender on one scene; renders of one seed run back to back."""
    h, w = ref.shape[:2]
    active, setup = [], {}
    for c in contenders:
        try:
            setup[c] = c.setup(scene_path)
            active.append(c)
        except Skip as e:
            print(f"  skipping {e}", file=sys.stderr)
    results = []
    for spp in spps:
        rs = {c: Result(scene_path.stem, c.name, c.sampler, spp, w * h, setup[c]) for c in active}
        for c in active:
            rs[c].warmup_s = c.warmup(spp)
        # Round robin over the contenders, so that a change of machine load hits all alike.
        for seed in seeds:
            for c in active:
                s = c.render(spp, seed)
                r = rs[c]
                r.render_s.append(s.render_s)
                r.wall_s.append(s.wall_s)
                r.cpu_s.append(s.cpu_s)
                r.relmse.append(relmse(s.img, ref))
        for c in active:
            r = rs[c]
            r.note = getattr(c, "note", "")
            if r.wall_s != r.render_s:  # a child process: loading, writing the image
                r.setup_s = mean(r.wall_s) - r.mean_time()
            log_result(r)
        for prefix in ("mitsuba", "mcrt"):
            b = best_of(list(rs.values()), prefix).get((scene_path.stem, spp))
            if b:
                print(f"  best {prefix} at {spp} spp: {b.label()} (eff {fmt(b.efficiency())})",
                      file=sys.stderr)
        results += rs.values()
    return results


# ---------------------------------------------------------------- images


def relmse(img, ref) -> float:
    """mean((img - ref)^2 / (ref^2 + 0.01)) over pixels and channels; inf if any NaN."""
    import numpy as np

    if img.shape != ref.shape:
        raise ValueError(f"image shape {img.shape} differs from the reference {ref.shape}")
    if not np.all(np.isfinite(img)):
        return float("inf")
    return float(np.mean((img - ref) ** 2 / (ref**2 + 0.01)))


def resolve(path: str) -> Path:
    """A path as given if it exists from here or is absolute, else relative to the repo."""
    p = Path(path)
    return p if p.is_absolute() or p.exists() else REPO / p


def reference_for(scene: str, defines: dict[str, str],
                  refs: dict[str, str] | None = None) -> tuple[Path, Path]:
    """Split 'scene.xml[:ref.exr]'. Without ':ref.exr' the reference is the one --ref gives
    for the scene (by its path as given, its file name or its stem), else <stem>.exr beside
    the scene, or <stem>-direct.exr with -D max_depth=2 (direct lighting only)."""
    path, _, ref = scene.partition(":")
    scene_path = resolve(path)
    refs = refs or {}
    ref = ref or next((refs[k] for k in (path, scene_path.name, scene_path.stem) if k in refs),
                      "")
    direct = "-direct" if defines.get("max_depth") == "2" else ""
    ref_path = resolve(ref) if ref else scene_path.with_name(f"{scene_path.stem}{direct}.exr")
    for p in (scene_path, ref_path):
        if not p.exists():
            fail(f"{p} does not exist")
    return scene_path, ref_path


# ---------------------------------------------------------------- report


def fmt(x: float, digits: int = 3) -> str:
    """Format a float with a number of significant digits; '–' for NaN."""
    return "–" if x != x else f"{x:.{digits}g}"


def markdown_table(results: list[Result], baseline: str = BASELINE) -> str:
    """The comparison as a Markdown table, grouped by scene and spp; the ratio columns divide
    by the best result whose label starts with `baseline` (marked 'baseline')."""
    base = best_of(results, baseline)
    vs = "best Mitsuba" if baseline == "mitsuba" else baseline
    lines = [
        "| scene | spp | renderer | sampler | load / overhead (s) | warm-up (s) | "
        f"render (s) | CPU (s) | M samples/s | relMSE | efficiency (1/s) | vs {vs} | "
        f"vs {vs}, CPU |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in sorted(results, key=lambda r: (r.scene, r.spp)):
        b = base.get((r.scene, r.spp))
        note = " ".join(x for x in ("(baseline)" if r is b else "", r.note) if x)
        ratio = r.efficiency() / b.efficiency() if b else float("nan")
        cpu_ratio = r.cpu_efficiency() / b.cpu_efficiency() if b else float("nan")
        lines.append(
            f"| {r.scene} | {r.spp} | {r.renderer} | {r.sampler} | {fmt(r.setup_s, 2)} | "
            f"{fmt(r.warmup_s, 3)} | {fmt(r.mean_time(), 3)} | {fmt(mean(r.cpu_s), 3)} | "
            f"{fmt(r.samples_per_s() / 1e6, 3)} | {fmt(r.mean_relmse(), 3)} | "
            f"{fmt(r.efficiency(), 3)} | {fmt(ratio, 3)} | "
            f"{fmt(cpu_ratio, 3)}{' ' + note if note else ''} |"
        )
    return "\n".join(lines) + "\n"


def best_table(results: list[Result], baseline: str = BASELINE) -> str:
    """Per scene and spp: the most efficient Mitsuba contender and the most efficient of ours,
    and the ratio of their efficiencies (by render time and by CPU time)."""
    mits, ours = best_of(results, baseline), best_of(results, "mcrt")
    lines = [
        "| scene | spp | best Mitsuba | efficiency (1/s) | best mcrt | efficiency (1/s) | "
        "mcrt ÷ Mitsuba | by CPU time |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for k in sorted(set(mits) | set(ours)):
        m, o = mits.get(k), ours.get(k)
        ratio = o.efficiency() / m.efficiency() if m and o else float("nan")
        cpu_ratio = o.cpu_efficiency() / m.cpu_efficiency() if m and o else float("nan")
        lines.append(
            f"| {k[0]} | {k[1]} | {m.label() if m else '–'} | "
            f"{fmt(m.efficiency()) if m else '–'} | {o.label() if o else '–'} | "
            f"{fmt(o.efficiency()) if o else '–'} | {fmt(ratio)} | {fmt(cpu_ratio)} |"
        )
    return "\n".join(lines) + "\n"


def machine_info(mi_version: str | None) -> dict:
    """Machine and tool versions, for the record."""
    info = {"nproc": os.cpu_count(), "python": platform.python_version(), "mitsuba": mi_version}
    try:
        with open("/proc/cpuinfo") as f:
            info["cpu"] = next(
                (ln.split(":", 1)[1].strip() for ln in f if ln.startswith("model name")), None
            )
    except OSError:
        info["cpu"] = platform.processor()
    try:
        info["rustc"] = subprocess.run(
            ["rustc", "--version"], capture_output=True, text=True
        ).stdout.strip()
    except OSError:
        info["rustc"] = None
    info["loadavg"] = os.getloadavg() if hasattr(os, "getloadavg") else None
    return info


def log_result(r: Result) -> None:
    """Print one finished configuration to stderr (progress)."""
    print(
        f"  {r.scene:12} {r.spp:5} spp  {r.renderer:28} {r.sampler:11} "
        f"time {fmt(r.mean_time())} s  relMSE {fmt(r.mean_relmse())}  "
        f"eff {fmt(r.efficiency())}",
        file=sys.stderr,
    )


# ---------------------------------------------------------------- main


def parse_args(argv=None) -> argparse.Namespace:
    """Command-line options."""
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("scenes", nargs="*", default=DEFAULT_SCENES,
                   help="scene files, optionally 'scene.xml:reference.exr' "
                        "(default: the Cornell box and Veach's MIS scene in mcrt-render/tests/data)")
    p.add_argument("-D", dest="define", action="append", default=[], metavar="NAME=VALUE",
                   help="scene parameter for both renderers (as the render example's -D)")
    p.add_argument("--spp", type=int, nargs="+", default=[64, 256], help="sample counts")
    p.add_argument("--repeats", type=int, default=2, help="seeds per configuration")
    p.add_argument("--ref", action="append", default=[], metavar="SCENE=EXR",
                   help="reference image of a scene (named by its path as given, its file "
                        "name or its stem); repeatable. Default: <stem>.exr beside the scene")
    p.add_argument("--variants", nargs="+", default=MITSUBA_VARIANTS,
                   help="Mitsuba variants (spaces or commas)")
    p.add_argument("--mitsuba-samplers", nargs="+", default=MITSUBA_SAMPLERS,
                   metavar="SAMPLER",
                   help="Mitsuba samplers, each replacing the scene's <sampler type=...>, "
                        "crossed with --variants (spaces or commas; default "
                        f"{','.join(MITSUBA_SAMPLERS)}; the scene's own type loads it unchanged)")
    p.add_argument("--samplers", nargs="+", default=["independent", "sobol"],
                   help="our samplers (spaces or commas; one the renderer rejects is skipped "
                        "with a message)")
    p.add_argument("--ours-args", nargs="+", default=[""], metavar="ARGS",
                   help="extra arguments for our renderer, one configuration each "
                        "(e.g. '' '--integrator bdpt'); crossed with --samplers, except a "
                        "configuration that names its own --sampler")
    p.add_argument("--baseline", default=BASELINE, metavar="PREFIX",
                   help="the ratio columns divide by the best result whose 'renderer "
                        "sampler' starts with this (default 'mitsuba': the best Mitsuba "
                        "variant and sampler; e.g. 'mitsuba llvm_ad_rgb independent')")
    p.add_argument("--renderer", type=Path, default=REPO / DEFAULT_BINARY,
                   help="our render binary")
    p.add_argument("--also-renderer", action="append", default=[], metavar="LABEL=PATH",
                   help="another build of our render example (e.g. one of an earlier commit), "
                        "run with the same configurations and shown as 'mcrt@LABEL': before "
                        "and after in one run (repeatable)")
    p.add_argument("--no-build", action="store_true", help="do not run cargo build first")
    p.add_argument("--threads", type=int, default=0,
                   help="threads for both renderers (default: all cores)")
    p.add_argument("--skip-mitsuba", action="store_true", help="only our renderer")
    p.add_argument("--skip-ours", action="store_true", help="only Mitsuba")
    p.add_argument("--quick", action="store_true",
                   help="smoke test: 16 spp, one seed, Cornell box only (unless scenes given)")
    p.add_argument("--json", type=Path, help="also write the results as JSON here")
    p.add_argument("--markdown", type=Path, help="also write the table here")
    a = p.parse_args(argv)
    if a.quick:
        a.spp, a.repeats = [16], 1
        if a.scenes == DEFAULT_SCENES:
            a.scenes = DEFAULT_SCENES[:1]
    if a.repeats < 1 or min(a.spp) < 1:
        p.error("--repeats and --spp must be positive")
    for k in ("variants", "mitsuba_samplers", "samplers"):
        setattr(a, k, [x for v in getattr(a, k) for x in v.split(",") if x])
    a.refs = {}
    for r in a.ref:
        k, sep, v = r.partition("=")
        if not sep or not k or not v:
            p.error(f"--ref {r}: expected SCENE=EXR")
        a.refs[k] = v
    a.others = []
    for r in a.also_renderer:
        k, sep, v = r.partition("=")
        if not sep or not k or not Path(v).exists():
            p.error(f"--also-renderer {r}: expected LABEL=PATH of an existing binary")
        a.others.append((k, Path(v)))
    a.defines = {}
    for d in a.define:
        k, sep, v = d.partition("=")
        if not sep or not k:
            p.error(f"-D {d}: expected NAME=VALUE")
        a.defines[k] = v
    return a


def main(argv=None) -> int:
    """Run the comparison and print the Markdown table on stdout."""
    a = parse_args(argv)
    variants = [] if a.skip_mitsuba else a.variants
    # mitsuba also reads the EXR files, so it is needed even for --skip-mitsuba.
    mi, dr = import_mitsuba(variants)
    mi.set_variant("scalar_rgb")
    if a.threads:
        dr.set_thread_count(a.threads)
    if not a.skip_ours:
        if not a.no_build:
            build_renderer(a.renderer)
        elif not a.renderer.exists():
            fail(f"renderer binary {a.renderer} missing: run "
                 "'cargo build --release --bin render' or drop --no-build")
    seeds = list(range(1, a.repeats + 1))
    results: list[Result] = []
    with tempfile.TemporaryDirectory(prefix="mcrt-peer-") as tmp:
        contenders = [MitsubaContender(mi, dr, v, a.defines, s)
                      for v in variants for s in a.mitsuba_samplers]
        if not a.skip_ours:
            seen = set()
            for label, binary in [("", a.renderer)] + a.others:
                for x in a.ours_args:
                    for s in a.samplers:
                        c = OursContender(binary, s, x, a.defines, a.threads, tmp, label)
                        if c.key() not in seen:  # one naming its own --sampler comes once
                            seen.add(c.key())
                            contenders.append(c)
        # Check every scene and reference before the first render.
        scenes = [reference_for(scene, a.defines, a.refs) for scene in a.scenes]
        for scene_path, ref_path in scenes:
            ref = read_exr(ref_path)
            print(f"{scene_path.name} (reference {ref_path.name}):", file=sys.stderr)
            results += measure_scene(contenders, scene_path, ref, a.spp, seeds)
    table = markdown_table(results, a.baseline) + "\n" + best_table(results, a.baseline)
    print(table)
    info = machine_info(mi.__version__)
    for out in (a.markdown, a.json):
        if out:
            out.parent.mkdir(parents=True, exist_ok=True)
    if a.markdown:
        a.markdown.write_text(table)
    if a.json:
        a.json.write_text(json.dumps(
            {"machine": info, "command": sys.argv, "seeds": seeds,
             "results": [dict(asdict(r), efficiency=r.efficiency(),
                              cpu_efficiency=r.cpu_efficiency()) for r in results]},
            indent=2))
    print(f"machine: {info}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
