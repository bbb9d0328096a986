#!/usr/bin/env python3
"""Mitsuba 3 and mcrt side by side: time, samples/s, relMSE and efficiency on the same scenes.

Usage:
    pip install mitsuba                      # Mitsuba 3 (PyPI), also brings numpy
    apt-get install -y libllvm19             # for the llvm_ad_rgb variant (Debian)
    scripts/compare_mitsuba.py [--scenes tests/data/cornell-box.xml ...] [--spp 64 256]
                               [--variants scalar_rgb llvm_ad_rgb] [--ours] [--sampler ...]

For each scene, sample count and Mitsuba variant: load the scene (timed), render once to warm
up (Mitsuba's JIT compiles its kernels there; timed and reported separately), then render again
with another seed and time that render alone. Our renderer (with --ours) runs as
`cargo run --release --example render -- SCENE --spp N -o OUT.exr [--sampler S]`; its time is
the render time it prints (`time X s, ...`), and the rest of the process's wall time (loading,
BVH build, image output) goes in the warm-up column; without such a line the wall time is used
and the row says so. The script builds the example once, untimed, before the first run.

relMSE = mean over pixels and RGB channels of (img − ref)² / (ref² + 0.01), against the
reference EXR in tests/data/ (see tests/data/REFERENCES.md); efficiency = 1 / (relMSE × time).
A scene with `-D max_depth=2` is compared with its `-direct` reference.
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time

REPO = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
DATA = os.path.join(REPO, "tests", "data")
LLVM_CANDIDATES = [
    "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1",
    "/usr/lib/x86_64-linux-gnu/libLLVM-19.so",
]


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--scenes", nargs="+", default=[
        os.path.join(DATA, "cornell-box.xml"), os.path.join(DATA, "veach-mis.xml")])
    p.add_argument("--spp", nargs="+", type=int, default=[64, 256])
    p.add_argument("--variants", nargs="+", default=["scalar_rgb", "llvm_ad_rgb"])
    p.add_argument("--define", "-D", action="append", default=[],
                   help="NAME=VALUE scene parameter, as the renderer's -D")
    p.add_argument("--ours", action="store_true", help="also run our renderer example")
    p.add_argument("--sampler", action="append", default=[],
                   help="our renderer's --sampler value(s) to run besides the scene's own")
    p.add_argument("--mitsuba", action=argparse.BooleanOptionalAction, default=True,
                   help="run Mitsuba (default); --no-mitsuba runs ours only")
    p.add_argument("--threads", type=int, default=0, help="threads for both (0: all cores)")
    return p.parse_args()


def reference_for(scene, defines):
    """The reference EXR of a scene file under the given -D parameters."""
    name = os.path.splitext(os.path.basename(scene))[0]
    if defines.get("max_depth") == "2":
        name += "-direct"
    path = os.path.join(os.path.dirname(os.path.abspath(scene)), name + ".exr")
    if not os.path.exists(path):
        path = os.path.join(DATA, name + ".exr")
    return path


def read_exr(path):
    """An EXR as a float64 array (height, width, 3), read with Mitsuba's Bitmap."""
    import mitsuba as mi
    import numpy as np
    bmp = mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, False)
    return np.array(bmp, dtype=np.float64)


def rel_mse(img, ref):
    import numpy as np
    img = np.asarray(img, dtype=np.float64)[..., :3]
    if img.shape != ref.shape:
        raise ValueError(f"image shape {img.shape} differs from the reference's {ref.shape}")
    return float(np.mean((img - ref) ** 2 / (ref ** 2 + 0.01)))


def setup_llvm():
    if "DRJIT_LIBLLVM_PATH" not in os.environ:
        for path in LLVM_CANDIDATES:
            if os.path.exists(path):
                os.environ["DRJIT_LIBLLVM_PATH"] = path
                break


def run_mitsuba(variant, scene, spp, defines, ref, threads):
    import mitsuba as mi
    mi.set_variant(variant)
    if threads:
        mi.Thread.thread_count = threads  # scalar variants; llvm uses drjit's pool
        import drjit as dr
        dr.set_thread_count(threads)
    params = dict(defines)
    params["spp"] = str(spp)
    t0 = time.perf_counter()
    sc = mi.load_file(scene, **params)
    load = time.perf_counter() - t0
    t0 = time.perf_counter()
    img = mi.render(sc, spp=spp, seed=0)
    _ = float(img.array[0]) if hasattr(img, "array") else None  # force evaluation
    warm = time.perf_counter() - t0
    t0 = time.perf_counter()
    img = mi.render(sc, spp=spp, seed=1)
    import numpy as np
    arr = np.array(img)  # forces evaluation of the JIT kernels
    render = time.perf_counter() - t0
    w, h = arr.shape[1], arr.shape[0]
    return dict(who=f"mitsuba {variant}", load=load, warm=warm, time=render,
                samples=w * h * spp, rel_mse=rel_mse(arr, ref))


def build_ours():
    subprocess.run(["cargo", "build", "--release", "--example", "render"], cwd=REPO, check=True)


def run_ours(scene, spp, defines, ref, sampler, threads):
    """HOOK: our renderer, through the `render` example (issue 4's CLI)."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.exr")
        cmd = ["cargo", "run", "--quiet", "--release", "--example", "render", "--",
               scene, "--spp", str(spp), "-o", out]
        for k, v in defines.items():
            cmd += ["-D", f"{k}={v}"]
        if sampler:
            cmd += ["--sampler", sampler]
        if threads:
            cmd += ["--threads", str(threads)]
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, cwd=REPO, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        if proc.returncode != 0:
            raise RuntimeError(f"{' '.join(cmd)} failed:\n{proc.stderr[-2000:]}")
        text = proc.stdout + proc.stderr
        # The example prints "time 1.234 s, ... M samples/s, ... (N samples, M rays)".
        m = re.search(r"\btime:?\s*([0-9.eE+-]+)\s*s\b", text)
        render = float(m.group(1)) if m else wall
        n = re.search(r"\((\d+) samples", text)
        img = read_exr(out)
    h, w = img.shape[:2]
    samples = int(n.group(1)) if n else w * h * spp
    return dict(who=f"mcrt {sampler or 'scene sampler'}" + ("" if m else " (wall time)"),
                load=float("nan"), warm=wall - render if m else float("nan"), time=render,
                samples=samples, rel_mse=rel_mse(img, ref))


def print_row(scene, spp, r):
    eff = 1.0 / (r["rel_mse"] * r["time"]) if r["rel_mse"] > 0 else float("inf")
    print(f"| {os.path.basename(scene)} | {spp} | {r['who']} | {r['load']:.3f} | "
          f"{r['warm']:.3f} | {r['time']:.3f} | {r['samples'] / r['time'] / 1e6:.2f} | "
          f"{r['rel_mse']:.4e} | {eff:.1f} |", flush=True)


def main():
    args = parse_args()
    setup_llvm()
    defines = dict(d.split("=", 1) for d in args.define)
    if args.ours:
        build_ours()
    print("| scene | spp | renderer | load s | warm-up s | render s | M samples/s | relMSE "
          "| efficiency 1/(relMSE·s) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for scene in args.scenes:
        ref_path = reference_for(scene, defines)
        ref = read_exr(ref_path)
        for spp in args.spp:
            if args.mitsuba:
                for variant in args.variants:
                    try:
                        print_row(scene, spp, run_mitsuba(variant, scene, spp, defines, ref,
                                                          args.threads))
                    except Exception as e:  # a missing variant or libLLVM: say so, go on
                        print(f"| {os.path.basename(scene)} | {spp} | mitsuba {variant} | "
                              f"failed: {e} |", flush=True)
            if args.ours:
                for sampler in [None] + args.sampler:
                    print_row(scene, spp, run_ours(scene, spp, defines, ref, sampler,
                                                   args.threads))


if __name__ == "__main__":
    sys.exit(main())
