#!/usr/bin/env bash
# test_compare_verdicts.sh - compare's speed verdicts on synthetic throughput.json files whose
# repetitions are written here, so every expected verdict follows from the definitions
# (compare.h) and the values below, worked out in the comments. No device.
#   - drift: a run slowed 2x in every absolute rate but not in its normalised rates is "same";
#     decided on absolute rates (--absolute) it is "slower";
#   - a planted 2x in the normalised rates: "slower", ratio 0.5 exactly (Hodges-Lehmann of
#     scaled copies), its interval around 0.5;
#   - a change beyond alpha but inside the threshold: "same"; the same change with a smaller
#     --min-change: "slower";
#   - repetitions spread over 0.5..2: "noisy";
#   - Holm over 20 rows: p = 2/252 each (5 vs 5 fully apart) is significant alone, not after
#     x 20 (the smallest adjusted p is 20 x 2/252 = 0.159);
#   - --fail-if-slower exits 1 on the planted rows only; a warning below 5 repetitions.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init

python3 - "$T" <<'PY' || bad "making the synthetic runs"
import json, os, sys
T = sys.argv[1]
def run(name, rows, cpu=True):
    res = []
    for label, reps, norm in rows:
        med = sorted(reps)[len(reps) // 2]
        r = {"label": label, "model": label, "variant": "default", "n_mode": "uniform", "status": "ok",
             "evals_per_s": {"min": min(reps), "median": med, "max": max(reps)}, "evals_per_s_reps": reps}
        r["normalised_cpu_reps" if cpu else "normalised_reps"] = norm
        res.append(r)
    os.makedirs(os.path.join(T, name))
    json.dump({"schema": "brdfbench.throughput/3", "context": {"device": "fake"}, "results": res},
              open(os.path.join(T, name, "throughput.json"), "w"))
base = [1.00, 1.01, 0.99, 1.02, 0.98]          # spread 4%: a 95% interval within the 10% band
absr = [1e9 * x for x in base]
run("base", [("m", absr, base)])
# drift: every absolute rate halved, normalised rates unchanged (the reference slowed too)
run("drift", [("m", [x / 2 for x in absr], list(base))])
# planted: the code twice as slow, absolute and normalised
run("planted", [("m", [x / 2 for x in absr], [x / 2 for x in base])])
# 4% slower, fully apart from the baseline (0.96 x 1.02 < 0.98; p = 2/252): inside the 10% threshold
run("small", [("m", absr, [x * 0.96 for x in base])])
# spread 0.5..2 around the same centre
run("noisy", [("m", absr, [0.5, 2.0, 1.0, 0.7, 1.4])])
# 20 rows, each 10% slower and fully apart; and their baseline
rows20 = [("m%d" % i, absr, base) for i in range(20)]
run("base20", rows20)
run("slow20", [(l, [x * 0.9 for x in a], [x * 0.9 for x in n]) for l, a, n in rows20])
# 3 repetitions per side
run("base3", [("m", absr[:3], base[:3])])
run("slow3", [("m", absr[:3], [x / 2 for x in base[:3]])])
PY

verdict() {   # verdict RUN_A RUN_B ROW [compare flags...] -> prints the cell's verdict and ratio
    local a=$1 b=$2 row=$3
    shift 3
    "$BIN" compare "$T/$a" "$T/$b" --out "$T/c_${a}_$b" --quiet "$@" 2>"$T/err" >/dev/null
    python3 - "$T/c_${a}_$b/compare.json" "$row" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
for r in d["rows"]:
    if r["key"].startswith(sys.argv[2] + " |"):
        c = r["cells"][1]
        print(c["verdict"], c["ratio"], c.get("ratio_ci_lo"), c.get("ratio_ci_hi"), c.get("p"), c.get("p_adjusted"), c.get("basis"))
PY
}

near() { python3 -c "import sys; assert abs(float(sys.argv[1]) - float(sys.argv[2])) <= 1e-12" "$1" "$2"; }
v=$(verdict base drift m)
read -r verd ratio rest <<<"$v"
[ "$verd" = same ] && near "$ratio" 1 && ok || bad "drift on normalised rates: '$v', expected same, ratio 1"
[[ $v == *"normalised per CPU second" ]] && ok || bad "drift: basis '$v'"
v=$(verdict base drift m --absolute)
read -r verd ratio rest <<<"$v"
[ "$verd" = slower ] && near "$ratio" 0.5 && ok || bad "drift on absolute rates: '$v', expected slower, ratio 0.5"
v=$(verdict base planted m)
read -r verd ratio lo hi p padj rest <<<"$v"
[ "$verd" = slower ] && ok || bad "planted 2x: '$v', expected slower"
python3 -c "import sys; r,lo,hi=map(float,sys.argv[1:]); assert abs(r-0.5)<1e-12 and lo<0.5<hi and hi<0.55 and lo>0.45" \
    "$ratio" "$lo" "$hi" && ok || bad "planted 2x: ratio $ratio in [$lo, $hi], expected 0.5 inside, within 10%"
# 5 vs 5 fully apart: p = 2 / C(10, 5)
python3 -c "import sys; assert abs(float(sys.argv[1]) - 2/252) < 1e-12" "$p" && ok || bad "planted: p $p, expected 2/252"
v=$(verdict base small m)
[[ $v == same* ]] && ok || bad "4% change, 10% threshold: '$v', expected same"
v=$(verdict base small m --min-change 1)
[[ $v == slower* ]] && ok || bad "4% change, 1% threshold: '$v', expected slower"
v=$(verdict base noisy m)
[[ $v == noisy* ]] && ok || bad "spread 0.5..2: '$v', expected noisy"
# Holm: 20 rows of p = 2/252 = 0.0079 each; adjusted, the smallest is 20 x 0.0079 = 0.159
v=$(verdict base20 slow20 m7)
[[ $v == slower* ]] && ok || bad "20 rows without Holm: '$v', expected slower"
v=$(verdict base20 slow20 m7 --holm)
read -r verd ratio lo hi p padj rest <<<"$v"
[ "$verd" != slower ] && ok || bad "20 rows with Holm: '$v', expected not slower"
python3 -c "import sys; assert abs(float(sys.argv[1]) - 20*2/252) < 1e-12" "$padj" && ok ||
    bad "Holm: adjusted p $padj, expected 20 x 2/252"
# 3 vs 3 can reach p = 0.1 at best: undecided at 0.05, and a warning
v=$(verdict base3 slow3 m)
[[ $v == undecided* ]] && ok || bad "3 repetitions: '$v', expected undecided"
grep -q "only 3 repetitions" "$T/err" && ok || bad "3 repetitions: no warning: $(cat "$T/err")"
# the CI condition: exit 1 naming the planted row, 0 on drift
expect 1 "throughput m \| default \| n uniform evals_per_s: 0\.5x" compare "$T/base" "$T/planted" --out "$T/f1" --fail-if-slower 10
"$BIN" compare "$T/base" "$T/drift" --out "$T/f2" --fail-if-slower 10 --quiet 2>"$T/err" && ok ||
    bad "drift must not fail --fail-if-slower: $(cat "$T/err")"
expect 2 "--min-change" compare "$T/base" "$T/drift" --min-change 150
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
