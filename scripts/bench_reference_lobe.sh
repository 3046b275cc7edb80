#!/usr/bin/env bash
# bench_reference_lobe.sh - what a user lobe model as the reference costs the lobe sweep
# (accuracy --reference FILE for a lobe model; docs/user-models.md, "A lobe model against a user
# lobe model"): the same user lobe (cq2's formula written out) against the built-in phong (the
# device evaluates the reference) and against c^n in a user file (a first launch writes the
# samples, the host evaluates the reference in double at each in its sandbox's child, and the
# comparing launch reads a table).
#
#   bash scripts/bench_reference_lobe.sh [RUNS]          (default 5 runs per case)
#
# Printed per case: the median wall seconds and the median CPU seconds (user + system, the
# sandbox's children included) of a whole `accuracy` run at the default grid (n in [2, 1000]
# step 1, 4096 samples per zone), each with its ratio to the built-in reference's median, and the
# machine's load. Environment: BRDFBENCH (default build/brdfbench). A benchmark, not a test: its
# figures go into notes, never into assertions.
set -euo pipefail
cd "$(dirname "$0")/.."
B=${BRDFBENCH:-build/brdfbench}
RUNS=${1:-5}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
cat >"$W/q.cl" <<'EOF2'
/* brdfbench-model
 * name: uq
 */
REAL uq(REAL c, REAL n)
{
    REAL b = 0.5f * n * (c - 1.0f) + 1.0f;
    return b > 0.0f ? b * b : 0.0f;
}
EOF2
cat >"$W/p.cl" <<'EOF2'
/* brdfbench-model
 * name: upw
 */
REAL upw(REAL c, REAL n) { return pow(c, n); }
EOF2
median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
time_case() {   # NAME ARGS...
    local name=$1
    shift
    "$B" accuracy "$@" --json "$W/warm.json" --quiet   # kernel builds out of the timing
    : >"$W/$name.wall"
    : >"$W/$name.cpu"
    for _ in $(seq "$RUNS"); do
        /usr/bin/time -f "%e %U %S" -o "$W/t" "$B" accuracy "$@" --json "$W/out.json" --quiet
        read -r wall user sys <"$W/t"
        echo "$wall" >>"$W/$name.wall"
        echo "$user + $sys" | bc -l >>"$W/$name.cpu"
    done
    median <"$W/$name.wall" >"$W/$name.med"
    median <"$W/$name.cpu" >"$W/$name.cmed"
}
time_case builtin --model-file "$W/q.cl" --reference phong
time_case userfile --model-file "$W/q.cl" --reference "$W/p.cl"
base=$(cat "$W/builtin.med")
cbase=$(cat "$W/builtin.cmed")
for c in builtin userfile; do
    m=$(cat "$W/$c.med")
    cm=$(cat "$W/$c.cmed")
    printf '%-9s median wall %.3f s (ratio %.2f), median CPU %.3f s (ratio %.2f), %d runs\n' "$c" "$m" \
        "$(echo "$m / $base" | bc -l)" "$cm" "$(echo "$cm / $cbase" | bc -l)" "$RUNS"
done
uptime
