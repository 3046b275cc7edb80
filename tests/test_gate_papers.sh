#!/usr/bin/env bash
# test_gate_papers.sh - CI runs the project's own gates file, tests/gates/papers.json: the
# papers' models as measured (each bound brackets a figure at its 4th significant digit), so
# a change that moves any of these figures fails the build. Three of its figures are derived
# independently in test_gate.sh (fq2's by brute force, cq2's and fq2n's in closed form).
set -u
BIN=${BRDFBENCH:?BRDFBENCH must name the brdfbench binary}
SRC=${SRC_DIR:?}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"

"$BIN" gate "$SRC/tests/gates/papers.json" --junit "$T/papers.xml" --json "$T/papers.json" >"$T/out" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
cat "$T/out"
[ $rc -eq 0 ] && ok || bad "papers.json: exit $rc: $(grep -v '^PASS' "$T/out"; cat "$T/err")"
gates=$(python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["gates"]))' "$SRC/tests/gates/papers.json")
[ "$(grep -c '^PASS  ' "$T/out")" -eq "$gates" ] && ok || bad "expected $gates PASS lines"
python3 - "$T/papers.json" "$T/papers.xml" <<'PY' && ok || bad "papers.json result files"
import json, sys, xml.etree.ElementTree as ET
d = json.load(open(sys.argv[1]))
assert d["summary"]["failed"] == 0 and d["summary"]["passed"] == d["summary"]["gates"]
# Every gate there carries both bounds, and the claimed figure (where a paper gives one) is
# reported beside the measured one, never used as a bound.
for g in d["gates"]:
    assert g["min"] is not None and g["max"] is not None, g
    assert "note" in g
root = ET.parse(sys.argv[2]).getroot()
assert root.get("failures") == "0" and root.get("tests") == str(d["summary"]["gates"])
PY
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
