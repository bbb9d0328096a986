#!/usr/bin/env bash
# Issue 28's efficiency figures, 1/(relMSE × time), through scripts/compare_mitsuba.py (which
# interleaves the contenders seed by seed, so a change of load hits all alike, and reports
# Mitsuba's best variant and sampler beside ours):
#   1. many-lights: our path tracer choosing lights by power (--light-bvh off) and by the
#      light BVH (--light-bvh on, the default there), against Mitsuba 3;
#   2. indirect: our path tracer against the guided one, against Mitsuba 3;
#   3. the plain Cornell box: the same (the cost of guiding where it has nothing to learn);
#   4. door (optional, DOOR=1): the same.
# The guided tracer's time includes its training passes (the render's own time, which the
# script reads from `render`'s "time" line), so its efficiency is at equal total time.
# Three seeds, llvm_ad_rgb with Mitsuba's independent, ldsampler and multijitter samplers.
# Run it on an idle machine: wall times are the point (the last column gives CPU time too).
#
# Usage: scripts/compare_issue28.sh [--quick] [OUT_DIR]
#   --quick: 16 spp, one seed (checks that it runs; the figures mean nothing).
set -euo pipefail
cd "$(dirname "$0")/.."
spp=(64 256 1024)
repeats=3
if [ "${1:-}" = "--quick" ]; then
  spp=(16)
  repeats=1
  shift
fi
out=${1:-out/issue28}
mkdir -p "$out"
export DRJIT_LIBLLVM_PATH=${DRJIT_LIBLLVM_PATH:-/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1}
data=mcrt-render/tests/data
common=(--no-build --variants llvm_ad_rgb --mitsuba-samplers independent ldsampler multijitter
  --samplers independent --repeats "$repeats" --spp "${spp[@]}")
cargo build --release --bin render

python3 scripts/compare_mitsuba.py "$data/issue28/many-lights.xml" "${common[@]}" \
  --ours-args "--light-bvh off" "--light-bvh on" \
  --json "$out/many-lights.json" --markdown "$out/many-lights.md"

python3 scripts/compare_mitsuba.py "$data/issue28/indirect.xml" "$data/cornell-box.xml" \
  "${common[@]}" --ours-args "--integrator path" "--integrator guided" \
  --json "$out/indirect-cornell.json" --markdown "$out/indirect-cornell.md"

if [ "${DOOR:-0}" = 1 ]; then
  python3 scripts/compare_mitsuba.py "$data/issue28/door.xml" "${common[@]}" \
    --ours-args "--integrator path" "--integrator guided" \
    --json "$out/door.json" --markdown "$out/door.md"
fi
echo "tables in $out/*.md"
