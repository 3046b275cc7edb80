#!/usr/bin/env bash
# test_ci_doc.sh - runs the shell commands of docs/ci.md (between its ci-commands markers) as
# written, with a small gates file and a short throughput run with a user lobe, against a
# baseline run of the same configuration: with nothing changed the pipeline passes (exit 0);
# with the lobe replaced by one of about twice the work (tests/ci/mylobe_2x.cl) it fails after
# its confirmation run, naming that lobe's rows and no other (exit 1); a missing baseline
# exits 2 without a confirmation run; a failing gate stops the pipeline (exit 1, JUnit
# failure); the run folder holds what the page says in every case. The two build lines are checked to be in the
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
# A small throughput configuration with a user lobe: its code is the only thing the planted
# run changes (tests/ci/mylobe_2x.cl: the same lobe under the same name with about twice the
# work). Ten repetitions, as the page advises.
tp_flags() { echo "--models cq2,fq2,mylobe --model-file $SRC/tests/ci/$1 --reps 10 --min-time 0.005 --work-items 8 --variants default --no-host-c --no-sweep"; }
"$BIN" throughput $(tp_flags mylobe.cl) --quiet --out "$T/base" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "the baseline's run: $(cat "$T/err")"

# SLOWER_PCT 25: the suite runs two tests at a time, and under the sanitizers, on a 2-core
# machine; the planted lobe is about 3x slower (0.33), far past it.
pipeline() {   # RUN BASELINE GATES LOBE_FILE
    (cd "$T" && BRDFBENCH="$BIN" RUN="$1" BASELINE="$2" GATES="$3" TP_FLAGS="$(tp_flags "$4")" SLOWER_PCT=25 \
        bash "$T/run.sh") >"$T/out" 2>"$T/err"
}

# Nothing changed (the same binary and lobe, timed again): the pipeline passes. This is a
# statistical claim, not a timing assertion: with the rates normalised by the reference
# kernel, a 25% threshold, Holm's correction over the rows and a confirmation run, identical
# code fails only if both runs call a row more than 25% slower at family-wise level 0.05.
pipeline "$T/run1" "$T/base" "$T/gates.json" mylobe.cl
rc=$?
[ $rc -eq 0 ] && ok || bad "pipeline with nothing changed: exit $rc: $(tail -5 "$T/err")"
for f in gates.xml gates.json throughput.json throughput.csv compare/compare.md compare/compare.csv \
    compare/compare.json compare/compare.png; do
    [ -s "$T/run1/$f" ] && ok || bad "run folder lacks $f"
done
grep -q '<testcase' "$T/run1/gates.xml" && ! grep -q '<failure' "$T/run1/gates.xml" && ok || bad "gates.xml: one passing case"
grep -q "mylobe | default | n uniform" "$T/out" && ok || bad "the compare table is in the log: $(head -c 300 "$T/out")"

# The planted slowdown: the lobe with twice the work fails the pipeline after its
# confirmation, every one of its rows named with both runs' ratios, and no other row.
pipeline "$T/run2" "$T/base" "$T/gates.json" mylobe_2x.cl
rc=$?
[ $rc -eq 1 ] && ok || bad "pipeline with the planted slowdown: exit $rc, expected 1: $(tail -5 "$T/err")"
for mode in uniform varying; do
    grep -qE "throughput mylobe \| default \| n $mode evals_per_s: 0\.[0-9]+x the baseline .*confirmed by confirm: 0\.[0-9]+x" "$T/err" \
        && ok || bad "planted: mylobe n $mode not named as confirmed: $(tail -8 "$T/err")"
done
# What fails is what both runs found slower (the lines of the confirmation's comparison, "confirmed
# by"): the first comparison's list is the candidates for the confirmation run, and a row that
# one run alone found slower (the machine busy with something else for a while) is no failure,
# as the page says; so only the confirmed lines are the verdict checked here.
[ "$(grep 'confirmed by confirm' "$T/err" | grep -vc ' mylobe | ')" -eq 0 ] && ok ||
    bad "planted: rows other than mylobe's failed: $(grep 'confirmed by confirm' "$T/err")"
[ -s "$T/run2/confirm/throughput.json" ] && [ -s "$T/run2/compare/compare.md" ] && ok ||
    bad "planted: the confirmation run or the comparison is missing"

# A baseline that is not there: exit 2 (no comparison could be made), no confirmation run.
pipeline "$T/run4" "$T/nobase" "$T/gates.json" mylobe.cl
rc=$?
[ $rc -eq 2 ] && [ ! -e "$T/run4/confirm" ] && ok || bad "missing baseline: exit $rc, expected 2 and no confirmation"

# a gate that fails stops the pipeline before throughput, with the failure in the JUnit file
sed 's/"max": 0.02/"max": 0.001/' "$T/gates.json" >"$T/gates_fail.json"
pipeline "$T/run3" "$T/base" "$T/gates_fail.json" mylobe.cl
rc=$?
[ $rc -eq 1 ] && ok || bad "failing gate: exit $rc, expected 1"
grep -q '<failure' "$T/run3/gates.xml" && [ ! -e "$T/run3/throughput.json" ] && ok || bad "failing gate: JUnit or order"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
