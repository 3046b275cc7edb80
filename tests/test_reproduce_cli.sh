#!/usr/bin/env bash
# test_reproduce_cli.sh - `brdfbench reproduce` and `brdfbench fit` end to end: the files and their
# contracts, a few measured values against closed forms worked here in python, the fitted
# model used by another command, and the error paths (message and exit code).
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init

INDEP=${INDEP:?INDEP must name the tests/indep binary}
# A lighter reproduce (coarser Q sweep; the best Q is refined by Brent all the same): every
# claim row is there, and each is checked against an independent value below.
"$BIN" reproduce --out "$T/rep" --q-step 0.05 --q-samples 256 >"$T/table" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "reproduce exit $rc: $(tail -c 500 "$T/err")"
for f in claims.json claims.md q_sweep.json energy.json; do
    [ -s "$T/rep/$f" ] && ok || bad "reproduce did not write $f"
done
grep -qE '^P1-eq11-lhs .*REPRODUCED' "$T/table" && ok || bad "table lacks the P1-eq11-lhs row"
grep -qE 'rows: [0-9]+ reproduced, [0-9]+ not reproduced' "$T/table" && ok || bad "table lacks its summary line"

jsoncheck reproduce_cli_claims_q_sweep "$T/rep" && ok || bad "claims.json / q_sweep.json contract and values"
# energy.json and physical.json (written only by reproduce's energy checks) against their JSON
# Schemas (docs/schemas/, as tests/test_machine_readable.sh does for the other kinds), and
# broken copies of them fail
for n in claims q_sweep energy physical; do
    jsoncheck schema_docs "$SRC/docs/schemas" "$T/rep/$n.json" && ok || bad "$n.json does not validate against its schema"
done
jsoncheck schema_broken "$SRC/docs/schemas" "$T/rep" energy physical && ok || bad "a broken energy.json or physical.json validates"

# Every one of the 44 rows: its measured value against one derived outside the program, and its
# verdict against the one that value gives under the paper's printed precision.
python3 "$(dirname "${BASH_SOURCE[0]}")/indep_claims.py" "$T/rep" "$INDEP" && ok || bad "claims.json against independent values"

# fit over [2, 1000]: fit.json's contract; the per-n limit at n = 2 is k = 1, max delta 0.
"$BIN" fit --n-min 2 --n-max 1000 --out "$T/fit" >"$T/fit_table" 2>"$T/err"
rc=$?
[ $rc -eq 0 ] && ok || bad "fit exit $rc: $(tail -c 500 "$T/err")"
model=$(jsoncheck reproduce_cli_fit_against_indep "$T/fit/fit.json" "$INDEP")
[ -n "$model" ] && ok || bad "fit.json contract"
spec=${model%% *}
maxrel=${model##* }
# The fitted model is a registry model with parameters: the accuracy command measures the same figure.
"$BIN" accuracy --models "$spec" --n-min 2 --n-max 1000 --out "$T/acc" >/dev/null 2>"$T/err" && ok || bad "accuracy --models $spec: $(cat "$T/err")"
jsoncheck reproduce_cli_fitted_model_accuracy "$T/acc/accuracy.json" "$maxrel" && ok || bad "accuracy of the fitted model differs from fit.json"

expect 2 "--samples" reproduce --samples 100
expect 2 "--q-step" reproduce --q-step 0
expect 2 "unknown option" reproduce --bogus
expect 2 "--max-abs" fit --max-abs 0
expect 2 "--max-abs" fit --max-abs 2
expect 2 "n-min" fit --n-min 5 --n-max 5
expect 2 "unknown option" fit --bogus

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
