#!/usr/bin/env bash
# bench_reference_table.sh - what a reference the host evaluates costs the hemisphere sweep
# (accuracy --reference FILE or merl:FILE.binary; docs/definitions.md, "Full BRDFs over the
# hemisphere", Reference): the same user model (Cook-Torrance GGX written out, k = 1.25) against
# the built-in ct-ggx:F0=0.04 (the device evaluates the reference) and against the same formula in
# a user file (the host evaluates it in double at every grid point, in its sandbox's child, and
# the device reads a table), and ct-ggx against a measured material (tests/merl_synth's GGX).
#
#   bash scripts/bench_reference_table.sh [RUNS]          (default 5 runs per case)
#
# Printed per case: the median wall seconds and the median CPU seconds (user + system, the
# sandbox's children included) of a whole `accuracy` run at the default grid (48x48x96, 8 axis
# values), each with its ratio to the built-in reference's median, and the machine's load. Environment:
# BRDFBENCH (default build/brdfbench), MERL_SYNTH (default build/tests/merl_synth). A benchmark,
# not a test: its figures go into notes, never into assertions.
set -euo pipefail
cd "$(dirname "$0")/.."
B=${BRDFBENCH:-build/brdfbench}
SYN=${MERL_SYNTH:-build/tests/merl_synth}
RUNS=${1:-5}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
cat >"$W/f.glsl" <<'EOF2'
/* brdfbench-model
 * name: fref
 * reference: ct-ggx
 * lobe: theta_h
 * param: F0 0 1 0.04
 */
float fref(vec3 L, vec3 V, vec3 N, float n, float F0)
{
    vec3 H = normalize(L + V);
    float nh = dot(N, H), vh = dot(V, H);
    float nl = max(dot(N, L), 1e-6), nv = max(dot(N, V), 1e-6);
    float a2 = 2.0 / (n + 2.0);
    float d = (1.0 - nh) * (1.0 + nh) + nh * nh * a2;
    float D = a2 / (3.14159265358979 * d * d);
    float F = F0 + (1.0 - F0) * pow(1.0 - vh, 5.0);
    float G = 2.0 * nl / (nl + sqrt(a2 + (1.0 - a2) * nl * nl)) * 2.0 * nv / (nv + sqrt(a2 + (1.0 - a2) * nv * nv));
    return D * F * G / (4.0 * nl * nv);
}
EOF2
sed 's/fref/kf/g; s/return D/return 1.25 * D/' "$W/f.glsl" >"$W/kf.glsl"
"$SYN" "$W/g.binary" ggx 0.25 0.04 1 0 >/dev/null
median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
time_case() {   # NAME ARGS...
    local name=$1
    shift
    "$B" accuracy "$@" --json "$W/warm.json" --quiet   # kernel builds out of the timing
    : >"$W/$name.wall"
    : >"$W/$name.cpu"
    for _ in $(seq "$RUNS"); do
        # wall seconds, and user + system CPU seconds of brdfbench and its sandbox's children
        /usr/bin/time -f "%e %U %S" -o "$W/t" "$B" accuracy "$@" --json "$W/out.json" --quiet
        read -r wall user sys <"$W/t"
        echo "$wall" >>"$W/$name.wall"
        echo "$user + $sys" | bc -l >>"$W/$name.cpu"
    done
    median <"$W/$name.wall" >"$W/$name.med"
    median <"$W/$name.cpu" >"$W/$name.cmed"
}
time_case builtin --model-file "$W/kf.glsl" --reference ct-ggx:F0=0.04
time_case userfile --model-file "$W/kf.glsl" --reference "$W/f.glsl"
time_case measured --models ct-ggx:F0=0.04 --reference "merl:$W/g.binary"
base=$(cat "$W/builtin.med")
cbase=$(cat "$W/builtin.cmed")
for c in builtin userfile measured; do
    m=$(cat "$W/$c.med")
    cm=$(cat "$W/$c.cmed")
    printf '%-9s median wall %.3f s (ratio %.2f), median CPU %.3f s (ratio %.2f), %d runs\n' "$c" "$m" \
        "$(echo "$m / $base" | bc -l)" "$cm" "$(echo "$cm / $cbase" | bc -l)" "$RUNS"
done
uptime
