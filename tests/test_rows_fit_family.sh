#!/usr/bin/env bash
# test_rows_fit_family.sh - the fit.json of `fit --family` carries its rows, and one of the
# previous version (brdfbench.fit_family/1, no rows) is read through its upgrade into the same
# rows; a run folder holding it gives its rows (kind fit_family), not a fit's.
#
# Where the expectations come from: the rows are written a second time here, in Python, from the
# file's own layout (fit, min_max_rel, min_max_abs, the trade-off list and the device block that
# docs/schemas/brdfbench.fit_family-2.schema.json describes). The old file is
# tests/fixtures/rows-v-previous/fit_family.json (its command in that folder's README.md).
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
cd "$T" || exit 1

cat >expect.py <<'PY'
import json, sys
# expect.py FIT_FILE ROWS_JSON: the rows brdfbench read equal those of the layout
f, rows = (json.load(open(p)) for p in sys.argv[1:3])
FIG = ("status", "reason", "cap", "cap_reason", "max_abs_cap", "max_rel", "max_rel_at_n", "max_abs", "max_abs_at_n", "model")
def point(o, cap_key):
    m = {k: ("neither", v) for k, v in o.items() if k not in FIG and isinstance(v, (int, float))}
    if cap_key and isinstance(o.get(cap_key), (int, float)):
        m["cap"] = ("neither", o[cap_key])
    m["max_rel"] = ("lower", o.get("max_rel"))
    if "max_rel_at_n" in o: m["max_rel.at_n"] = ("neither", o["max_rel_at_n"])
    m["max_abs"] = ("lower", o.get("max_abs"))
    if "max_abs_at_n" in o: m["max_abs.at_n"] = ("neither", o["max_abs_at_n"])
    return m
want = {}
for name in ("fit", "min_max_rel", "min_max_abs"):
    st = f[name].get("status", "ok")
    want[name] = (st, point(f[name], "cap"))
for i, t in enumerate(f["tradeoff"]):
    want["tradeoff %d of %d" % (i + 1, len(f["tradeoff"]))] = ("ok", point(t, "max_abs_cap"))
dev = f["device"]
want["device"] = (dev.get("status", "ok"), point(dev, None) if dev.get("status", "ok") == "ok" else {})
assert rows["source"]["kind"] == "fit_family", rows["source"]
got = {r["row"]: (r["status"], {m["name"]: (m["direction"], m["value"]) for m in r["metrics"]}) for r in rows["rows"]}
assert got == want, "\n".join("%s: read %r, expected %r" % (k, got.get(k), want.get(k)) for k in sorted(set(got) | set(want)) if got.get(k) != want.get(k))
assert rows["context"]["family fit"] == "%s, objective %s" % (f["family"], f["objective"]), rows["context"]
PY

OLD="$SRC/tests/fixtures/rows-v-previous/fit_family.json"
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if d["schema"] == "brdfbench.fit_family/1" and "rows" not in d else 1)' \
    "$OLD" && ok || bad "the fixture fit_family.json is not a fit_family/1 file without rows"
"$BIN" rows "$OLD" --format json --output old.rows.json 2>err && ok || bad "rows (old family fit): $(cat err)"
python3 expect.py "$OLD" old.rows.json && ok || bad "old family fit: the upgrade's rows differ from the layout's"

"$BIN" fit --family pow3 --n-min 2 --n-max 6 --samples 16 --out run --quiet >/dev/null 2>err || bad "fit --family: $(cat err)"
rows_both_ways run/fit.json brdfbench.fit_family/2 brdfbench.fit_family/1 expect.py
# the run folder: its fit.json is read once, as a family fit
"$BIN" rows run --format json --output folder.rows.json 2>err && ok || bad "rows of the folder: $(cat err)"
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); docs = d if isinstance(d, list) else [d]; sys.exit(0 if [x["source"]["kind"] for x in docs] == ["fit_family"] else 1)' \
    folder.rows.json && ok || bad "the folder's rows: $(head -c 300 folder.rows.json)"
# two family runs compare (pairing the points by their place)
"$BIN" compare run run --out cmp --quiet >out 2>err && ok || bad "compare of two family fits: $(cat err)"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
