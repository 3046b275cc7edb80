#!/usr/bin/env bash
# test_rows_field.sh - a heatmap's field file (field_MODEL.json) carries its rows, and one of the
# previous version (brdfbench.field/1, no rows) is read through its upgrade into the same rows.
#
# Where the expectations come from: the rows are written a second time here, in Python, from the
# file's own layout (the members docs/schemas/brdfbench.field-2.schema.json describes: the peaks'
# value, n and x, the check block); the program's rows, from a new file's rows member and from an
# old file's layout, must be those. The old file is the field_fq2.json of
# tests/fixtures/run-v48575e2 (written by the version before, commit 48575e2).
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
cd "$T" || exit 1

cat >expect.py <<'PY'
import json, math, sys
# expect.py FIELD_FILE ROWS_JSON: the rows brdfbench read equal those of the layout
f, rows = (json.load(open(p)) for p in sys.argv[1:3])
want = {}
for peak, name in (("epicentre_max_rel", "epicentre.max_rel"), ("attenuation_max_abs", "attenuation.max_abs")):
    p = f[peak]
    want[name] = ("1", "lower", p["value"])
    want[name + ".at_n"] = ("1", "neither", p["n"])
    want[name + ".at_x"] = ("rad", "neither", p["x"])
for k in ("max_rel_diff", "max_abs_diff"):
    want["check." + k] = ("1", "lower", f["check"][k])
assert rows["source"]["kind"] == "field", rows["source"]
assert len(rows["rows"]) == 1, len(rows["rows"])
r = rows["rows"][0]
assert r["keys"] == {"model": f["model"]} and r["attributes"] == {"reference": f["reference"]}, (r["keys"], r["attributes"])
got = {m["name"]: (m["unit"], m["direction"], m["value"]) for m in r["metrics"]}
assert got == want, (got, want)
g = f["grid"]
ctx = "%d n x %d x, n %g..%g log-spaced, attenuation to %g x_e" % (g["rows"], g["cols"], g["n_min"], g["n_max"], g["u_max"])
assert rows["context"]["heatmap grid"] == ctx, (rows["context"].get("heatmap grid"), ctx)
PY

# 1. an old field file reads through the upgrade
tar -xJf "$SRC/tests/fixtures/run-v48575e2/run.tar.xz" ./field_fq2.json && mv field_fq2.json old_field_fq2.json
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if d["schema"] == "brdfbench.field/1" and "rows" not in d else 1)' \
    old_field_fq2.json && ok || bad "the fixture's field_fq2.json is not a field/1 file without rows"
"$BIN" rows old_field_fq2.json --format json --output old.rows.json 2>err && ok || bad "rows (old field): $(cat err)"
python3 expect.py old_field_fq2.json old.rows.json && ok || bad "old field: the upgrade's rows differ from the layout's"

# 2. a new field file carries its rows; the same file as the previous version wrote it reads the same
"$BIN" accuracy --models fq2 --n-max 40 --samples 64 --pictures --out run >/dev/null 2>err || bad "accuracy --pictures: $(cat err)"
rows_both_ways run/field_fq2.json brdfbench.field/2 brdfbench.field/1 expect.py
# 3. a run folder's rows leave the field files out (the accuracy rows hold the refined maxima)
"$BIN" rows run --format json --output folder.rows.json 2>err && ok || bad "rows of the folder: $(cat err)"
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); docs = d if isinstance(d, list) else [d]; sys.exit(0 if all(x["source"]["kind"] != "field" for x in docs) else 1)' \
    folder.rows.json && ok || bad "the folder's rows include a field file"
# 4. the heatmap is redrawn from the new file
"$BIN" heatmap run >out 2>err && [ -s run/heatmap_fq2.png ] && ok || bad "heatmap redraw of a field/2 file: $(cat err)"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
