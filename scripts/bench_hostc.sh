#!/usr/bin/env bash
# bench_hostc.sh - is brdfbench's "tuned C" baseline tuned C? Its rate for fvol and fq2 beside
# the rate of a plain OpenMP loop doing the same evaluations, compiled here, measured in the
# same run, alternating: loop, brdfbench, loop, brdfbench... ROUNDS times.
#
#   bash scripts/bench_hostc.sh [ROUNDS]        (default 5)
#
# The plain loop: 20 lines of C, -O3 -march=native -fopenmp, OMP_NUM_THREADS = the threads of
# brdfbench's C baseline (the online CPUs), inputs made from the index (c uniform over [0, 1),
# n = 100, as throughput's uniform mode with --uniform-n 100), the model's formula written
# out, the values summed. brdfbench: `throughput --models fvol,fq2 --n-modes uniform
# --variants default --no-sweep`, its host_c.evals_per_s.median per model (each the median
# of --reps launches), and its device rate beside. Printed per model: the medians over the
# rounds and the ratio loop / brdfbench C (goal: within 3x). A benchmark, not a test: its
# figures go into notes, never into assertions.
#
# Environment: BRDFBENCH (default build/brdfbench), CC (default cc), TP_FLAGS (extra flags).
set -euo pipefail
cd "$(dirname "$0")/.."
B=${BRDFBENCH:-build/brdfbench}
ROUNDS=${1:-5}
CC=${CC:-cc}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
THREADS=$(getconf _NPROCESSORS_ONLN)

cat > "$W/loop.c" <<'C'
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
int main(int argc, char **argv)
{
    const long N = 1L << 28;                       /* evaluations per timed pass */
    const float n = 100.0f, k = argv[1][1] == 'v' ? 0.463f * n : 0.448f * n + 0.099f;  /* fvol, fq2 */
    double best = 0, sum = 0;
    for (int pass = 0; pass < 5; ++pass) {
        double t0 = omp_get_wtime(), total = 0;
#pragma omp parallel for reduction(+ : total) schedule(static)
        for (long b = 0; b < N / 4096; ++b) {
            float acc = 0;
#pragma omp simd reduction(+ : acc)
            for (int j = 0; j < 4096; ++j) {
                float c = (float)(b * 4096 + j) * (1.0f / (float)N);
                float base = k * (c - 1.0f) + 1.0f;
                base = base > 0.0f ? base : 0.0f;
                acc += base * base;
            }
            total += acc;
        }
        double rate = (double)N / (omp_get_wtime() - t0);
        best = rate > best ? rate : best;   /* the fastest pass: the loop's own best */
        sum = total;
    }
    printf("%.6g %.6g\n", best, sum);
    return 0;
}
C
$CC -O3 -march=native -fopenmp "$W/loop.c" -o "$W/loop"
export OMP_NUM_THREADS=$THREADS

for r in $(seq 1 "$ROUNDS"); do
    for m in fvol fq2; do
        echo "$r $m $("$W/loop" "$m" | cut -d' ' -f1)" >> "$W/loop.txt"
    done
    "$B" throughput --models fvol,fq2 --n-modes uniform --uniform-n 100 --variants default --no-sweep --quiet \
        ${TP_FLAGS:-} --json "$W/tp$r.json" >/dev/null
done

python3 - "$W" "$ROUNDS" "$THREADS" <<'PY'
import json, statistics, sys
w, rounds, threads = sys.argv[1], int(sys.argv[2]), sys.argv[3]
loop = {}
for line in open(w + "/loop.txt"):
    r, m, rate = line.split()
    loop.setdefault(m, []).append(float(rate))
bc, dev, st = {}, {}, {}
for r in range(1, rounds + 1):
    d = json.load(open(f"{w}/tp{r}.json"))
    for row in d["results"]:
        if row["variant"] != "default" or row["n_mode"] != "uniform" or row["label"] not in ("fvol", "fq2"):
            continue
        h = row["host_c"]
        st.setdefault(row["label"], []).append(h.get("sums_check", {}).get("status", h["status"]))
        if h["status"] == "ok":
            bc.setdefault(row["label"], []).append(h["evals_per_s"]["median"])
        dev.setdefault(row["label"], []).append(row["evals_per_s"]["median"])
print(f"{rounds} rounds, {threads} threads; medians over the rounds, G evaluations/s")
print(f"{'model':6} {'plain OpenMP loop':>18} {'brdfbench C':>12} {'loop / C':>9} {'device':>8}  sums check")
for m in ("fvol", "fq2"):
    l = statistics.median(loop[m]) * 1e-9
    c = statistics.median(bc[m]) * 1e-9 if bc.get(m) else float("nan")
    dv = statistics.median(dev[m]) * 1e-9
    print(f"{m:6} {l:18.3g} {c:12.3g} {l / c:9.2f} {dv:8.3g}  {','.join(sorted(set(st[m])))}")
PY
