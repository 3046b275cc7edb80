#!/bin/bash
# bench_hemisphere.sh - the hemisphere sweep's cost per evaluated sample against the lobe sweep's
# (a benchmark, never a test; the goal is at most 2x), on PoCL and on Mesa's rusticl (llvmpipe)
# where it is installed. Per platform and REPS runs interleaved, the median device seconds per
# sample (each sample evaluates a model and its reference) of
#   lobe:        brdfbench accuracy --model 'b=pow(c,n)' --reference blinn --samples 16384 (n 2..1000 step 2)
#   hemisphere:  brdfbench accuracy --model-file blinn_full.glsl --reference blinn, pow(N.H, n) of
#                normalised vectors, 32 values of n over 48x48x96 (its passes, not the probe's launch,
#                counted in its device time; the samples of the figures pass counted as points)
#   hemisphere built-in: --models ct-ggx against ct-ggx:F0=0.04 (a heavier BRDF, for scale)
# and their ratio. usage: scripts/bench_hemisphere.sh [REPS]   (default 5)
set -euo pipefail
B=${BRDFBENCH:-build/brdfbench}
REPS=${1:-5}
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
export MESA_SHADER_CACHE_DIR="$out/mesa-cache"
cat >"$out/blinn_full.glsl" <<'EOF2'
float blinn_full(vec3 L, vec3 V, vec3 N, float n)
{
    return pow(max(dot(N, normalize(L + V)), 0.0), n);
}
EOF2
# ns per sample of one run's accuracy.json (lobe: timing of results[0]; hemisphere: of its row)
per_point() {
    python3 -c "
import json, sys
rows = json.load(open(sys.argv[1]))['results']
t = rows[0]['timing']
print(t['device_seconds'] / t['points'] * 1e9)" "$1"
}
med() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
run_platform() {
    local name=$1; shift
    local lobe=() hemi=() ct=()
    for i in $(seq "$REPS"); do
        "$B" accuracy --model 'b=pow(c,n)' --reference blinn --n-step 2 --samples 16384 "$@" --json "$out/l.json" \
            >/dev/null 2>&1
        lobe+=("$(per_point "$out/l.json")")
        "$B" accuracy --model-file "$out/blinn_full.glsl" --reference blinn --axis-points 32 "$@" \
            --json "$out/h.json" >/dev/null 2>&1
        hemi+=("$(per_point "$out/h.json")")
        "$B" accuracy --models ct-ggx --reference ct-ggx:F0=0.04 --axis-points 32 "$@" --json "$out/c.json" \
            >/dev/null 2>&1
        ct+=("$(per_point "$out/c.json")")
    done
    local ml mh mc
    ml=$(med "${lobe[@]}"); mh=$(med "${hemi[@]}"); mc=$(med "${ct[@]}")
    echo "$name: lobe sweep (b = pow(c,n) vs blinn):        median $ml ns/sample (${lobe[*]})"
    echo "$name: hemisphere (blinn_full.glsl vs blinn):     median $mh ns/sample (${hemi[*]})"
    echo "$name: hemisphere (ct-ggx vs ct-ggx:F0=0.04):     median $mc ns/sample (${ct[*]})"
    awk -v a="$ml" -v b="$mh" -v c="$mc" -v n="$name" 'BEGIN {printf "%s: hemisphere / lobe = %.2f (blinn), %.2f (ct-ggx)\n", n, b / a, c / a}'
}
run_platform PoCL
P=$(RUSTICL_ENABLE=llvmpipe "$B" list 2>/dev/null | sed -n 's/^  platform \([0-9]*\): rusticl.*/\1/p' | head -1)
if [ -n "$P" ]; then
    RUSTICL_ENABLE=llvmpipe run_platform rusticl --platform "$P"
else
    echo "rusticl: not installed here (mesa-opencl-icd, RUSTICL_ENABLE=llvmpipe): skipped"
fi
