#!/usr/bin/env bash
# test_rows_claims.sh - claims.json, q_sweep.json and physical.json carry their rows, and the
# claims page (claims.md, report.md's "Claims of the papers") is drawn from them: by reproduce
# from the rows it writes, by report from the rows it reads back, through the upgrade functions
# for the files of the previous version.
#
# Where the expectations come from:
# - tests/rows_layouts.py maps each file's layout (claims, Q/max_rel/..., cost.rows and
#   he_terms) to rows a second time, in Python: the rows read from a new file's rows member and
#   from an old file's layout must be those.
# - the same new file read with its rows member taken out and its schema set to the previous
#   version (the upgrade function's path) gives the same rows document.
# - tests/fixtures/claims-v-previous/: claims.md as the previous version (6c15f72) wrote it,
#   with the physically based models' section: report.md's claims section drawn from that
#   version's files must be that page embedded as report.md embeds a page (its title dropped,
#   its headings one level down: the rule is written here again, in Python), byte for byte.
#   The same for a new run's own claims.md, with claims.md taken out of the folder first (so
#   the section cannot come from it).
# - compare of the previous run against the new one: what each metric's direction means for a
#   verdict (neither: changed or unchanged, never better, worse, faster or slower).
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
cd "$T" || exit 1
LAYOUTS="$SRC/tests/rows_layouts.py"
KINDS="claims q_sweep physical"
mkdir old && tar -C old -xJf "$SRC/tests/fixtures/claims-v-previous/run.tar.xz" || { echo "cannot unpack the fixture"; exit 1; }

# 1. the previous version's files read through the upgrade functions: rows as the layout says
for k in $KINDS; do
    python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if d["schema"] == sys.argv[2] and "rows" not in d else 1)' \
        "old/$k.json" "brdfbench.$k/1" && ok || bad "fixture $k.json is not a brdfbench.$k/1 file without rows"
    "$BIN" rows "old/$k.json" --format json --output "old_$k.rows.json" 2>"$T/err" && ok || bad "rows $k (old): $(cat "$T/err")"
    python3 "$LAYOUTS" "old/$k.json" "old_$k.rows.json" && ok || bad "old $k.json: the upgrade's rows differ from its layout's"
done

# the kinds a user may name list these three (the list comes from the kinds' table)
expect 2 "--kind: 'plots' is not a kind of result \(accepted: .*claims, q_sweep, physical" rows old --kind plots
expect 2 "--kind: 'plots' is not a kind of result \(accepted: .*claims, q_sweep, physical" history old old --kind plots
# `rows` of the folder with --kind: that kind's file alone
"$BIN" rows old --kind q_sweep --format json --output kind_q.rows.json 2>"$T/err" && ok || bad "rows --kind q_sweep: $(cat "$T/err")"
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if d["source"]["kind"] == "q_sweep" else 1)' \
    kind_q.rows.json && ok || bad "rows --kind q_sweep read another kind"

# embed PAGE REPORT OUT: REPORT with its claims section replaced by PAGE as report.md embeds a
# page: the page's "# " title line dropped, a '#' before every other line that starts with '#',
# then a blank line
embed() {
    python3 - "$@" <<'PY'
import sys
page, report, out = sys.argv[1:4]
lines = open(page).read().split("\n")
if lines and lines[0].startswith("# "):
    lines = lines[1:]
if lines and lines[-1] == "":
    lines = lines[:-1]
body = "".join(("#" + l if l.startswith("#") else l) + "\n" for l in lines) + "\n\n"
text = open(report).read()
head = "## Claims of the papers\n\n"
a = text.index(head) + len(head)
b = text.index("## Beyond the papers")
open(out, "w").write(text[:a] + body + text[b:])
PY
}

# 2. report.md of a run folder holding the previous version's claims files (a run folder of
#    that time, tests/fixtures/run-v48575e2, with them put in): the claims section is the
#    previous version's claims.md, physically based models' section included
mkdir run && tar -C run -xJf "$SRC/tests/fixtures/run-v48575e2/run.tar.xz" || { echo "cannot unpack the run fixture"; exit 1; }
cp old/claims.json old/claims.md old/q_sweep.json old/physical.json run/
embed old/claims.md run/report.md expected_old.txt
rm run/claims.md
"$BIN" report run --output report_old.txt 2>"$T/err" && ok || bad "report of the previous version's claims: $(cat "$T/err")"
cmp -s expected_old.txt report_old.txt && ok || bad "report's claims section differs from the previous version's claims.md: $(diff expected_old.txt report_old.txt | head -6)"
grep -q "^### Physically based models: cost, terms, albedo" report_old.txt && ok || bad "no physically based models' section"

# 3. a new run: each file carries its rows under its new schema; the rows member against the
#    layout mapping and against the upgrade function's reading of the same file
"$BIN" reproduce --samples 64 --no-grid-check --q-step 0.1 --q-samples 64 --q-n-step 50 --no-energy --out new \
    >/dev/null 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "$pass passed, $fail failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "reproduce exit $rc: $(tail -c 400 "$T/err")"
for k in $KINDS; do
    python3 - "new/$k.json" "brdfbench.$k/2" "brdfbench.$k/1" "up_$k.json" <<'PY' && ok || bad "new $k.json: schema or rows member"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["schema"] == sys.argv[2], d["schema"]
assert set(d["rows"]) >= {"context", "disturbed_reps", "devices", "rows"} and d["rows"]["rows"], sorted(d["rows"])
del d["rows"]
d["schema"] = sys.argv[3]
json.dump(d, open(sys.argv[4], "w"))
PY
    "$BIN" rows "new/$k.json" --format json --output "new_$k.rows.json" 2>"$T/err" && ok || bad "rows $k: $(cat "$T/err")"
    "$BIN" rows "up_$k.json" --format json --output "up_$k.rows.json" 2>"$T/err" && ok || bad "rows $k (upgrade): $(cat "$T/err")"
    python3 "$LAYOUTS" "new/$k.json" "new_$k.rows.json" && ok || bad "new $k.json: its rows member differs from its layout's"
    python3 - "new_$k.rows.json" "up_$k.rows.json" <<'PY' && ok || bad "new $k.json: rows member and upgrade function read differently"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
del a["source"]["schema"], b["source"]["schema"]
assert a == b, [k for k in a if a[k] != b[k]]
PY
done
# the claims' words are in the rows: each row's verdict as claims.json's layout gives it
python3 - new/claims.json <<'PY' && ok || bad "claims rows: texts or attributes differ from the layout's"
import json, sys
d = json.load(open(sys.argv[1]))
rows = {r["keys"]["id"]: r for r in d["rows"]["rows"]}
assert len(rows) == len(d["claims"]) > 30, len(rows)
for c in d["claims"]:
    r = rows[c["id"]]
    assert r["attributes"] == {"kind": c["kind"], "source": c["source"]}, r["attributes"]
    for k in ("claim", "claimed_text", "measured_text", "tolerance", "verdict", "note", "method"):
        assert r["texts"][k] == c[k], (c["id"], k)
    assert r["status"] == "ok", r["status"]   # a verdict is no failure to measure
PY

# 4. report.md's claims section from the new rows is reproduce's claims.md (claims.md taken out
#    of the folder first), and a verdict changed in the rows member is what the section shows
rm -rf run2 && mkdir run2 && tar -C run2 -xJf "$SRC/tests/fixtures/run-v48575e2/run.tar.xz"
rm run2/claims.md && cp new/claims.json new/q_sweep.json new/physical.json run2/
embed new/claims.md run2/report.md expected_new.txt
"$BIN" report run2 --output report_new.txt 2>"$T/err" && ok || bad "report of the new claims: $(cat "$T/err")"
cmp -s expected_new.txt report_new.txt && ok || bad "report's claims section differs from claims.md: $(diff expected_new.txt report_new.txt | head -6)"
python3 - run2/claims.json <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
d["rows"]["rows"][0]["texts"]["verdict"] = "tampered verdict"
json.dump(d, open(sys.argv[1], "w"))
PY
"$BIN" report run2 --output report_tampered.txt 2>"$T/err"
grep -q '\*\*tampered verdict\*\*' report_tampered.txt && ok || bad "the section does not show the rows' verdict"
# the physically based models' section needs physical.json when the claims say it is there
rm run2/physical.json
expect 2 'run2/physical.json: missing \(run.json records its part as done\)' report run2 --output -

# 5. compare of the previous run against the new one: the claims' and the Q sweep's figures are
#    values (claimed, measured, Q: changed or unchanged) or errors (max_rel: better or worse),
#    the cost rows' rates speeds; no claim's figure gets better, worse, faster or slower
"$BIN" compare old new --json cmp.json >/dev/null 2>"$T/err" && ok || bad "compare old new: $(cat "$T/err")"
python3 - cmp.json <<'PY' && ok || bad "compare old new: verdicts of the claims rows"
import json, sys
c = json.load(open(sys.argv[1]))
rows = [r for r in c["rows"] if r["kind"] in ("claims", "q_sweep", "physical")]
kinds = {r["kind"] for r in rows}
assert kinds == {"claims", "q_sweep", "physical"}, kinds
sense = {(r["kind"], r["metric"]): r["sense"] for r in rows}
assert sense[("claims", "measured")] == sense[("claims", "claimed")] == "value", sense
assert sense[("q_sweep", "max_rel")] == "error" and sense[("q_sweep", "Q")] == "value", sense
assert sense[("physical", "evaluations_per_s")] == "speed" and sense[("physical", "ratio_to_fq2")] == "value", sense
for r in rows:
    v = r["cells"][1]["verdict"]
    if r["sense"] == "value":
        assert v in ("unchanged", "changed", "missing"), (r["key"], r["metric"], v)
    assert r["cells"][1]["status"] == "ok" or r["cells"][1]["verdict"] == "missing", (r["key"], r["metric"])
# the claims whose figure is a number are paired across the runs; a claim that is not one has none
claims = {(r["key"], r["metric"]) for r in rows if r["kind"] == "claims"}
old = json.load(open("old/claims.json"))["claims"]
want = {(x["id"], m) for x in old for m in ("claimed", "measured") if x[m] is not None}
assert want <= claims, sorted(want - claims)[:5]
PY

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
