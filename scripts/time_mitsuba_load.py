#!/usr/bin/env python3
"""Times Mitsuba 3 loading the loader bench's PLY file (10^6 triangles), to compare with
`cargo bench -p mcrt-render --bench loader -- mesh_1m`: the `ply` shape alone (read, transform, bounding
box) and a scene holding it (that plus Mitsuba's acceleration structure).

    cargo bench -p mcrt-render --bench loader -- mesh_1m     # writes target/bench-data/torus-1000000.ply
    python3 scripts/time_mitsuba_load.py [--variant scalar_rgb|llvm_ad_rgb] [--repeats 5]

Prints the best and the median of the repeats, in seconds. Run it on an idle machine.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

from contenders import import_mitsuba

REPO = Path(__file__).resolve().parent.parent
DEFAULT = REPO / "target" / "bench-data" / "torus-1000000.ply"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("file", nargs="?", type=Path, default=DEFAULT)
    ap.add_argument("--variant", default="scalar_rgb")
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    if not args.file.exists():
        print(f"{args.file} is missing: run `cargo bench -p mcrt-render --bench loader -- mesh_1m` first",
              file=sys.stderr)
        return 1
    mi, dr = import_mitsuba([args.variant])
    mi.set_variant(args.variant)
    shape = {"type": "ply", "filename": str(args.file)}
    for name, make in [
        ("ply shape", lambda: mi.load_dict(shape)),
        ("scene (with BVH)", lambda: mi.load_dict({"type": "scene", "mesh": shape})),
    ]:
        make()  # warm-up: plugin loading, JIT
        times = []
        for _ in range(args.repeats):
            t0 = time.perf_counter()
            obj = make()
            dr.eval()
            dr.sync_thread()
            times.append(time.perf_counter() - t0)
            del obj
        print(f"{name}: best {min(times):.3f} s, median {statistics.median(times):.3f} s "
              f"({args.variant}, {args.repeats} runs)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
