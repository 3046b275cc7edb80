#!/usr/bin/env bash
# test_gate_papers.sh - CI runs the project's own gates file, tests/gates/papers.json: the
# papers' models as measured (each bound brackets a figure at its 4th significant digit), so
# a change that moves any of these figures fails the build. The pins are regression guards, not
# evidence: every one of the 16 measured figures is also compared here with a value derived
# outside the program (tests/indep.c's brute force over both zones of every n, from the formulas
# written a second time in tests/lobe_formulas.h; fq2n's figures in closed form), and the pinned
# bounds must hold that value too.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init

"$BIN" gate "$SRC/tests/gates/papers.json" --junit "$T/papers.xml" --json "$T/papers.json" >"$T/out" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
cat "$T/out"
[ $rc -eq 0 ] && ok || bad "papers.json: exit $rc: $(grep -v '^PASS' "$T/out"; cat "$T/err")"
gates=$(python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["gates"]))' "$SRC/tests/gates/papers.json")
[ "$(grep -c '^PASS  ' "$T/out")" -eq "$gates" ] && ok || bad "expected $gates PASS lines"
jsoncheck gate_papers_papers_result_files "$T/papers.json" "$T/papers.xml" && ok || bad "papers.json result files"
jsoncheck gate_papers_papers_figures_against_independent_values "$T/papers.json" "${INDEP:?INDEP must name the tests/indep binary}" && ok || bad "papers.json figures against independent values"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
