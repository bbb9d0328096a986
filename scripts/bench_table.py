#!/usr/bin/env python3
"""Markdown tables of ns per call from criterion's output (target/criterion).

Usage: scripts/bench_table.py [--pivot] [PREFIX ...] [!EXCLUDED_PREFIX ...]
       e.g.  scripts/bench_table.py --pivot warp distribution sampler

For every benchmark whose group id starts with a PREFIX, prints the median time per call and the
fastest sample's time per call (time per iteration / elements per iteration). On a loaded
machine the fastest sample is the better estimate of the cost; the median shows the noise.
With --pivot, one row per group and one column per operation, each cell
"fastest (median)". With --rate, elements per second instead of time per call (the group's
throughput: samples or rays for `render/`), with the speed-up over the group's first row.
"""

import json
import os
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "target", "criterion")


def load(directory):
    """(group, function, elements, median ns/iter, fastest ns/iter) of one benchmark."""
    new = os.path.join(directory, "new")
    with open(os.path.join(new, "benchmark.json")) as f:
        meta = json.load(f)
    with open(os.path.join(new, "estimates.json")) as f:
        median = json.load(f)["median"]["point_estimate"]
    with open(os.path.join(new, "sample.json")) as f:
        sample = json.load(f)
    fastest = min(t / n for t, n in zip(sample["times"], sample["iters"]))
    elements = (meta.get("throughput") or {}).get("Elements", 1)
    function = meta["function_id"]
    if meta.get("value_str"):
        function = f"{function} ({meta['value_str']})"
    return meta["group_id"], function, elements, median, fastest


def fmt(ns):
    if ns >= 1e6:
        return f"{ns / 1e6:.2f} ms"
    if ns >= 1e3:
        return f"{ns / 1e3:.2f} µs"
    return f"{ns:.1f} ns"


ORDER = ["new", "build", "sample", "sample_with_pdf", "next_2d", "start_pixel_sample", "pdf",
         "pmf", "invert"]


def op_rank(op):
    for i, name in enumerate(ORDER):
        if op == name or op.startswith(name + " "):
            return i
    return len(ORDER)


def pivot(rows):
    ops = []
    for r in rows:
        if r[1] not in ops:
            ops.append(r[1])
    ops.sort(key=op_rank)
    groups = []
    for r in rows:
        if r[0] not in groups:
            groups.append(r[0])
    cells = {(r[0], r[1]): r for r in rows}
    print("| benchmark | " + " | ".join(ops) + " |")
    print("|---|" + "---|" * len(ops))
    for g in groups:
        out = []
        for op in ops:
            r = cells.get((g, op))
            out.append(f"{fmt(r[4] / r[2])} ({fmt(r[3] / r[2])})" if r else "")
        print(f"| {g} | " + " | ".join(out) + " |")


def rate(rows):
    print("| benchmark | run | M per s, fastest sample (median) | speed-up (fastest) |")
    print("|---|---|---|---|")
    first = {}
    for group, function, elements, median, fastest in rows:
        best = elements / fastest * 1e3
        base = first.setdefault(group, best)
        print(f"| {group} | {function} | {best:.3f} ({elements / median * 1e3:.3f}) | "
              f"{best / base:.2f}× |")


def main():
    args = sys.argv[1:]
    pivoted = "--pivot" in args
    rated = "--rate" in args
    args = [a for a in args if a != "--rate"]
    excluded = [a[1:] for a in args if a.startswith("!")]
    prefixes = [a for a in args if a != "--pivot" and not a.startswith("!")] or [""]
    rows = []
    for group_dir in sorted(os.listdir(ROOT)):
        path = os.path.join(ROOT, group_dir)
        for root, dirs, files in os.walk(path):
            if os.path.basename(root) == "new" and "benchmark.json" in files:
                rows.append(load(os.path.dirname(root)))
    rows = [r for r in rows if any(r[0].startswith(p) for p in prefixes)
            and not any(r[0].startswith(p) for p in excluded)]
    rows.sort(key=lambda r: (r[0], r[1]))
    if pivoted:
        pivot(rows)
        return
    if rated:
        rate(rows)
        return
    print("| benchmark | operation | fastest sample per call | median per call |")
    print("|---|---|---|---|")
    for group, function, elements, median, fastest in rows:
        print(f"| {group} | {function} | {fmt(fastest / elements)} | {fmt(median / elements)} |")


if __name__ == "__main__":
    main()
