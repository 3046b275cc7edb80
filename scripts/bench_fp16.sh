#!/usr/bin/env bash
# bench_fp16.sh - what the fp16 evaluation of a half model costs in `brdfbench accuracy`: the
# spherical-Gaussian Phong lobe written in half (tests/test_shaderlang_files/phongapprox_half.hlsl,
# swept twice: fp32 and its fp16 build, then probed at each per-n maximum) against the same
# lobe in float (phongapprox_float.hlsl, one sweep). A benchmark, not a test: it asserts
# nothing; it prints the median wall time of REPEATS runs of each (kernels cached after the
# first run, which is not counted), their ratio, and the half model's fp32 and fp16 figures.
#
#   scripts/bench_fp16.sh [BUILD_DIR] [REPEATS]     (defaults: build, 5)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
repeats=${2:-5}
bin=$build/brdfbench
[ -x "$bin" ] || { echo "bench_fp16: $bin is missing (build first)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
grid=(--n-min 2 --n-max 1000 --n-step 1 --samples 4096)
median() { sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
run() {  # run FILE: wall seconds of one accuracy run
    local t0 t1
    t0=$(date +%s.%N)
    "$bin" accuracy --quiet --model-file "$1" "${grid[@]}" --json "$tmp/a.json" >/dev/null
    t1=$(date +%s.%N)
    echo "$t1 - $t0" | bc -l
}
half=tests/test_shaderlang_files/phongapprox_half.hlsl
flt=tests/test_shaderlang_files/phongapprox_float.hlsl
run "$half" >/dev/null; run "$flt" >/dev/null   # builds cached
th=$(for ((i = 0; i < repeats; ++i)); do run "$half"; done | median)
tf=$(for ((i = 0; i < repeats; ++i)); do run "$flt"; done | median)
run "$half" >/dev/null
python3 - "$tmp/a.json" "$th" "$tf" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["results"][0]
th, tf = float(sys.argv[2]), float(sys.argv[3])
f = r["fp16"]
print("accuracy, n in [2, 1000] step 1, 4096 samples per zone (median wall time of the runs)")
print("  half lobe (fp32 + fp16 sweeps): %.3f s   float lobe (fp32 sweep): %.3f s   ratio %.2f" % (th, tf, th / tf))
print("  sgphong fp32: max delta %.4g, max Delta %.4g" % (r["epicentre"]["max_rel"], r["attenuation"]["max_abs"]))
print("  sgphong fp16: max delta %.4g (%.3gx), max Delta %.4g (%.3gx), %d invalid" % (
    f["max_rel"], f["ratio_rel_to_fp32"], f["max_abs"], f["ratio_abs_to_fp32"], f["invalid_count"]))
PY
