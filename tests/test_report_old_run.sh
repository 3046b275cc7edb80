#!/usr/bin/env bash
# test_report_old_run.sh - `brdfbench report` of a run folder written by the previous version
# (accuracy.json brdfbench.accuracy/1, the files before they carried their rows) gives the
# report.md that version gave, byte for byte.
#
# Where the expectation comes from: tests/fixtures/run-v48575e2/run.tar.xz holds the folder and
# the report.md the binary of commit 48575e2 printed for it (the commands in its README.md); it
# was not written by this version.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
cd "$T" || exit 1
mkdir old && tar -C old -xJf "$SRC/tests/fixtures/run-v48575e2/run.tar.xz" || { echo "cannot unpack the fixture"; exit 1; }
cp old/report.md expected-report.txt
python3 -c 'import json,sys; sys.exit(0 if json.load(open(sys.argv[1]))["schema"] == "brdfbench.accuracy/1" else 1)' \
    old/accuracy.json && ok || bad "the fixture's accuracy.json is not brdfbench.accuracy/1"
"$BIN" report old >"$T/out" 2>"$T/err" && ok || bad "report of the old run: $(cat "$T/err")"
cmp -s expected-report.txt old/report.md && ok || bad "report.md differs from the previous version's: $(diff expected-report.txt old/report.md | head -5)"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
