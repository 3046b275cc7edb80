#!/usr/bin/env bash
# test_report_rows.sh - report.md's accuracy table, fit section and image passes are drawn from
# the rows of accuracy.json, fit.json and render.json, not from the files' own layout: a figure
# or a text changed in a file's rows member alone is what report.md shows.
#
# Where the expectations come from: the old run folder (tests/fixtures/run-v48575e2) with its
# three files rewritten as the version written now (the layout as it is, plus the rows member
# `brdfbench rows` reads from it); the edits are made here in the rows member only, and each
# expected cell is formatted here in Python the way the report's table prints it (%.4g of the
# percentage, the verdict's sentence as it is, a picture link's target as given).
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
cd "$T" || exit 1
mkdir run && tar -C run -xJf "$SRC/tests/fixtures/run-v48575e2/run.tar.xz" || { echo "cannot unpack the fixture"; exit 1; }

# each file as the current version writes it: its layout and its rows member
declare -A NOW=([accuracy]=brdfbench.accuracy/3 [fit]=brdfbench.fit/3 [render]=brdfbench.render/3)
for k in accuracy fit render; do
    "$BIN" rows "run/$k.json" --format json --output "$k.rows.json" 2>err && ok || bad "rows $k: $(cat err)"
    python3 - "run/$k.json" "$k.rows.json" "${NOW[$k]}" <<'PY' && ok || bad "$k.json: not rewritten with its rows"
import json, sys
d, r = (json.load(open(p)) for p in sys.argv[1:3])
d["schema"] = sys.argv[3]
d["rows"] = {k: r[k] for k in ("context", "disturbed_reps", "devices", "rows", "texts") if k in r}
json.dump(d, open(sys.argv[1], "w"))
PY
done
# as rewritten, the report is the old one still (the rows say what the layout says)
"$BIN" report run --output same_report.txt 2>err && ok || bad "report: $(cat err)"
cmp -s same_report.txt run/report.md && ok || bad "the rows member gives another report: $(diff run/report.md same_report.txt | head -5)"

# the edits, in the rows members only
python3 - <<'PY'
import json
a = json.load(open("run/accuracy.json"))
row = [r for r in a["rows"]["rows"] if r["model"] == "fq2"][0]
[m for m in row["metrics"] if m["name"] == "epicentre.max_rel"][0]["value"] = 0.0123456
json.dump(a, open("run/accuracy.json", "w"))
f = json.load(open("run/fit.json"))
f["rows"]["texts"]["verdict"] = "a verdict written in the rows alone"
json.dump(f, open("run/fit.json", "w"))
r = json.load(open("run/render.json"))
row = [x for x in r["rows"]["rows"] if x["model"] == "cq2" and x["attributes"].get("scene_name") == "spheres"
       and "reference" in x["attributes"]][0]
row["texts"]["image"] = "render/spheres/fq2.png"   # a file that exists: the link shows it
json.dump(r, open("run/render.json", "w"))
PY
"$BIN" report run --output edited_report.txt 2>err && ok || bad "report (edited): $(cat err)"
# fq2's max delta: 100 * 0.0123456 with 4 significant digits
want=$(python3 -c 'print("| `fq2` | `phong` | %.4g%% |" % (100 * 0.0123456))')
grep -qF "$want" edited_report.txt && ok || bad "accuracy table: fq2's max delta is not the rows' ($want)"
grep -qxF "a verdict written in the rows alone" edited_report.txt && ok || bad "fit section: the verdict is not the rows' text"
grep -qE '^\| `cq2` \| `phong` \|.*\| \[image\]\(render/spheres/fq2\.png\) ' edited_report.txt && ok \
    || bad "image passes: cq2's image link is not the rows' file"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
