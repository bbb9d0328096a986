#!/usr/bin/env bash
# The light count above which the renderer chooses lights by the light BVH (issue 28):
# efficiency of the BVH against the choice without it (by power over distance up to 16
# lights, by power beyond) on the many-lights room cut to N rectangle lights, from
#   - the error per sample: relMSE at a fixed spp against a 64×64 render of 1024 spp,
#     mean over three seeds;
#   - the cost per sample: callgrind's instruction count of an 8-spp render minus a 4-spp
#     render (scene loading and the BVH build cancel), per sample.
# No wall times (they mean nothing on a loaded machine).
#
# Usage: scripts/light_bvh_threshold.sh [N ...]   (default: 8 16 17 32 64 128)
# Needs: target/release/render, valgrind, python3 with numpy and mitsuba (EXR reading).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=target/release/render
out=${OUT:-/tmp/light-bvh-threshold}
mkdir -p "$out"
counts=("$@")
[ ${#counts[@]} -eq 0 ] && counts=(8 16 17 32 64 128)
python3 scripts/make_issue28_scenes.py --out "$out" --threshold-study "${counts[@]}" >/dev/null
res="-D res=64"
instr() { # scene mode spp -> instructions
  valgrind --tool=callgrind --callgrind-out-file="$out/cg.out" "$bin" "$1" $res --spp "$3" \
    --threads 1 --light-bvh "$2" -o "$out/cg.exr" >/dev/null 2>"$out/cg.log"
  grep -o 'Collected : [0-9]*' "$out/cg.log" | grep -o '[0-9]*$' ||
    grep -m1 '^summary:' "$out/cg.out" | grep -o '[0-9]*'
}
printf "%6s %12s %12s %12s %12s %10s\n" N "relMSE off" "relMSE on" "instr/s off" "instr/s on" "eff on/off"
for n in "${counts[@]}"; do
  sc="$out/many-lights-$n.xml"
  "$bin" "$sc" $res --spp 1024 --light-bvh on -o "$out/ref-$n.exr" >/dev/null
  declare -A rel=()
  for mode in off on; do
    files=()
    for seed in 1 2 3; do
      "$bin" "$sc" $res --spp 8 --seed "$seed" --light-bvh "$mode" -o "$out/$mode-$n-$seed.exr" >/dev/null
      files+=("$out/$mode-$n-$seed.exr")
    done
    rel[$mode]=$(python3 - "$out/ref-$n.exr" "${files[@]}" <<'EOF'
import sys, numpy as np, mitsuba as mi
mi.set_variant("scalar_rgb")
load = lambda p: np.array(mi.Bitmap(p).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, False), dtype=np.float64)
ref = load(sys.argv[1])
print(np.mean([np.mean((load(f) - ref) ** 2 / (ref ** 2 + 1e-3)) for f in sys.argv[2:]]))
EOF
)
  done
  samples=$((64 * 64 * 4))
  c_off=$(( ($(instr "$sc" off 8) - $(instr "$sc" off 4)) / samples ))
  c_on=$(( ($(instr "$sc" on 8) - $(instr "$sc" on 4)) / samples ))
  eff=$(python3 -c "print(f'{(${rel[off]} * $c_off) / (${rel[on]} * $c_on):.2f}')")
  printf "%6s %12.5f %12.5f %12s %12s %10s\n" "$n" "${rel[off]}" "${rel[on]}" "$c_off" "$c_on" "$eff"
done
