#!/usr/bin/env python3
"""Fills the generated tables of docs/performance.md from target/criterion.

Usage: scripts/perf_doc.py   (after the three `cargo bench --features bench --bench ...`; scripts/run_benches.sh
runs all of it)

Replaces the text between `<!-- table:NAME -->` and `<!-- end -->` markers with the output of
scripts/bench_table.py for that table (and of `cargo run --release --example
sampler_convergence` for the convergence table), and the machine block with this machine's
description.
"""

import os
import re
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
DOC = os.path.join(HERE, "..", "docs", "performance.md")
TABLES = {
    "warps": ["--pivot", "warp/", "!warp/vs"],
    "rand_distr": ["warp/vs"],
    "distributions": ["distribution/"],
    "samplers": ["--pivot", "sampler/"],
    "render_threads": ["--rate", "render/"],
}


def machine():
    info = {}
    with open("/proc/cpuinfo") as f:
        for line in f:
            key, _, value = line.partition(":")
            info.setdefault(key.strip(), value.strip())
    model = info.get("model name", "unknown")
    if "cache size" in info:
        model += f", cache {info['cache size']}"
    if "cpu MHz" in info:
        model += f", {float(info['cpu MHz']):.0f} MHz"
    simd = [f for f in ("avx2", "avx512f") if f in info.get("flags", "").split()]
    model += f", {'/'.join(simd) or 'no AVX2'}"
    nproc = subprocess.run(["nproc"], capture_output=True, text=True).stdout.strip()
    rustc = subprocess.run(["rustc", "--version"], capture_output=True, text=True).stdout.strip()
    log = os.path.join(HERE, "..", "target", "criterion", "loadavg.txt")
    load = ", ".join(open(log).read().split("\n")).strip(", ") if os.path.exists(log) else "?"
    return (f"- CPU: {model}, `nproc` = {nproc}\n- {rustc}\n"
            f"- load average (1, 5, 15 min) at the start and end of the bench run (UTC): {load}\n")


def main():
    text = open(DOC).read()
    for name, args in TABLES.items():
        table = subprocess.run(["python3", os.path.join(HERE, "bench_table.py"), *args],
                               capture_output=True, text=True, check=True).stdout
        text = re.sub(rf"(<!-- table:{name} -->\n).*?(<!-- end -->)",
                      lambda m: m.group(1) + table + m.group(2), text, flags=re.S)
    conv = subprocess.run(["cargo", "run", "--quiet", "--release", "--example",
                           "sampler_convergence"], cwd=os.path.join(HERE, ".."),
                          capture_output=True, text=True, check=True).stdout.strip() + "\n"
    text = re.sub(r"(<!-- table:convergence -->\n).*?(<!-- end -->)",
                  lambda m: m.group(1) + conv + m.group(2), text, flags=re.S)
    text = re.sub(r"(<!-- machine -->\n).*?(<!-- end -->)",
                  lambda m: m.group(1) + machine() + m.group(2), text, flags=re.S)
    open(DOC, "w").write(text)


if __name__ == "__main__":
    main()
