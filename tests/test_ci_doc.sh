#!/usr/bin/env bash
# test_ci_doc.sh - runs the shell commands of docs/ci.md (between its ci-commands markers) as
# written, with a small gates file and a short throughput run, against baselines made from a
# real run with every rate divided or multiplied by 1000, so the outcome is known without a
# timing assertion: a far slower baseline passes (exit 0), a far faster one fails the slowdown
# check (exit 1, rows named), a failing gate stops the pipeline (exit 1, JUnit failure); the run
# folder holds what the page says in every case. The two build lines are checked to be in the
# page (and in its workflow) but not run: the suite runs from that build already.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init

DOC="$SRC/docs/ci.md"
sed -n '/<!-- ci-commands:begin -->/,/<!-- ci-commands:end -->/p' "$DOC" | sed '1,2d;$d' | sed '$d' >"$T/block.sh"
grep -q '^set -eu$' "$T/block.sh" && [ "$(wc -l <"$T/block.sh")" -gt 10 ] && ok || bad "docs/ci.md: no command block"
for line in 'cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo' 'cmake --build build -j"$(nproc)"'; do
    grep -qxF "$line" "$T/block.sh" && ok || bad "docs/ci.md: build line missing: $line"
done
# every command of the block is also a step of the workflow, word for word
sed -n '/^```yaml/,/^```$/p' "$DOC" >"$T/workflow.yml"
grep -v -e '^#' -e '^ *$' -e '^set ' -e '^[A-Z_]*=\${' "$T/block.sh" | sed 's/ *#.*//' | while IFS= read -r cmd; do
    grep -qF -- "$cmd" "$T/workflow.yml" || echo "$cmd"
done >"$T/not_in_workflow"
[ ! -s "$T/not_in_workflow" ] && ok || bad "commands of the block missing from the workflow: $(cat "$T/not_in_workflow")"
# the block as it runs here: the build lines skipped
sed 's/^cmake /: skipped cmake /' "$T/block.sh" >"$T/run.sh"

cat >"$T/gates.json" <<'EOF'
{"gates": [{"model": "fq2", "metric": "epicentre.max_rel", "n_min": 2, "n_max": 40, "samples": 256, "max": 0.02}]}
EOF
TP_FLAGS="--models cq2,fq2 --reps 5 --min-time 0.002 --work-items 8 --variants default --no-host-c --no-sweep"
"$BIN" throughput $TP_FLAGS --quiet --out "$T/real" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "the baseline's run: $(cat "$T/err")"
for s in 0.001:slow 1000:fast; do
    python3 - "$T/real/throughput.json" "${s%%:*}" "$T/base_${s##*:}" <<'PY' || bad "making baseline $s"
import json, os, sys
d = json.load(open(sys.argv[1]))
f = float(sys.argv[2])
for r in d["results"]:
    for k in ("min", "median", "max"):
        r["evals_per_s"][k] *= f
    r["evals_per_s_reps"] = [x * f for x in r["evals_per_s_reps"]]
os.makedirs(sys.argv[3])
json.dump(d, open(os.path.join(sys.argv[3], "throughput.json"), "w"))
PY
done

pipeline() {   # RUN BASELINE GATES
    (cd "$T" && BRDFBENCH="$BIN" RUN="$1" BASELINE="$2" GATES="$3" TP_FLAGS="$TP_FLAGS" SLOWER_PCT=5 \
        bash "$T/run.sh") >"$T/out" 2>"$T/err"
}

# a baseline 1000 times slower: every row faster, exit 0, the run folder complete
pipeline "$T/run1" "$T/base_slow" "$T/gates.json"
rc=$?
[ $rc -eq 0 ] && ok || bad "pipeline against a slow baseline: exit $rc: $(tail -5 "$T/err")"
for f in gates.xml gates.json throughput.json throughput.csv compare/compare.md compare/compare.csv \
    compare/compare.json compare/compare.png; do
    [ -s "$T/run1/$f" ] && ok || bad "run folder lacks $f"
done
grep -q '<testcase' "$T/run1/gates.xml" && ! grep -q '<failure' "$T/run1/gates.xml" && ok || bad "gates.xml: one passing case"
grep -q "faster" "$T/out" && ok || bad "the compare table is in the log: $(head -c 300 "$T/out")"

# a baseline 1000 times faster: the slowdown check fails and names the rows; the folder stays
pipeline "$T/run2" "$T/base_fast" "$T/gates.json"
rc=$?
[ $rc -eq 1 ] && ok || bad "pipeline against a fast baseline: exit $rc, expected 1"
grep -qE "cq2 \| default \| n uniform evals_per_s: 0\.0[0-9]*x the baseline" "$T/err" && ok || bad "slow rows not named: $(tail -5 "$T/err")"
[ -s "$T/run2/compare/compare.md" ] && [ -s "$T/run2/throughput.json" ] && ok || bad "failed run lost its folder"

# a gate that fails stops the pipeline before throughput, with the failure in the JUnit file
sed 's/"max": 0.02/"max": 0.001/' "$T/gates.json" >"$T/gates_fail.json"
pipeline "$T/run3" "$T/base_slow" "$T/gates_fail.json"
rc=$?
[ $rc -eq 1 ] && ok || bad "failing gate: exit $rc, expected 1"
grep -q '<failure' "$T/run3/gates.xml" && [ ! -e "$T/run3/throughput.json" ] && ok || bad "failing gate: JUnit or order"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
