#!/usr/bin/env bash
# test_throughput_page_old.sh - report.md's Throughput section of a throughput.json written by the
# previous version (brdfbench.throughput/4, its rows without the page's record), with every build
# option, the tuned C loop and the accuracy sweep: the section that version gave, byte for byte,
# drawn from the file's rows alone (its throughput.md is removed first).
#
# Where the expectation comes from: tests/fixtures/throughput-v61a5e59/run.tar.xz holds the files
# and the report.md the binary of commit 61a5e59 printed for them (README.md there); it was not
# written by this version.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
cd "$T" || exit 1
mkdir old && tar -C old -xJf "$SRC/tests/fixtures/throughput-v61a5e59/run.tar.xz" || { echo "cannot unpack the fixture"; exit 1; }
mv old/report.md expected-report.txt
# the fixture is what it says: the previous schema, rows without the page's texts, and every part
# of the page (build options, C loop, sweep) in its throughput.md
python3 - old/throughput.json old/throughput.md <<'PY' && ok || bad "the fixture is not the previous version's full throughput part"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["schema"] == "brdfbench.throughput/4" and "texts" not in d["rows"], d["schema"]
md = open(sys.argv[2]).read()
assert "**build options:" in md and "accuracy sweep (" in md and "| fq2 | uniform |" in md, md[:200]
PY
rm old/throughput.md
"$BIN" report old --output "$T/out.md" 2>"$T/err" && ok || bad "report of the old folder: $(cat "$T/err")"
cmp -s expected-report.txt "$T/out.md" && ok || bad "report.md differs from the previous version's: $(diff expected-report.txt "$T/out.md" | head -5)"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
