#!/bin/sh
# Runs the benchmark files and rewrites the tables of docs/performance.md.
# The load average before and after goes to target/criterion/loadavg.txt (the doc quotes it).
set -e
cd "$(dirname "$0")/.."
mkdir -p target/criterion
{ printf 'start %s: ' "$(date -u +%H:%M)"; cut -d' ' -f1-3 /proc/loadavg; } > target/criterion/loadavg.txt
cargo bench --features bench --bench warps
cargo bench --features bench --bench distributions
cargo bench --features bench --bench samplers
cargo bench --features bench -p mcrt-render --bench render_threads
cargo bench --features bench -p mcrt-render --bench accel
{ printf 'end %s: ' "$(date -u +%H:%M)"; cut -d' ' -f1-3 /proc/loadavg; } >> target/criterion/loadavg.txt
python3 scripts/perf_doc.py
