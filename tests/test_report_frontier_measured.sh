#!/usr/bin/env bash
# test_report_frontier_measured.sh - the "Which lobe to ship" and "Measured materials" sections
# of report.md are drawn from the rows of frontier.json and measured.json, and the pages the
# engines wrote beside them (frontier.md, measured.md) are the same function of the same rows:
# `report RUN` prints what `all` wrote, each section is its page, and the same run with its
# frontier.json in brdfbench.frontier/2's form and its measured.json in brdfbench.measured/1's
# form (read through the upgrade functions) gives the same report. The teapot pass of the
# frontier keeps its own folder (frontier_teapot/render.json), whose PSNR frontier.json shows.
#
# Where the expectations come from: the report.md `all` wrote (the bytes `report` must give
# again); the table rows and figures of the pages written a second time in Python from the
# layouts of frontier.json and measured.json (the members docs/schemas/ describes), with the
# formats docs/frontier.md and docs/measured.md show; fq2's PSNR from frontier_teapot/render.json.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
SYN=${MERL_SYNTH:?MERL_SYNTH must name the merl_synth writer}
cd "$T" || exit 1
"$SYN" m.binary blinn 64 2.5 0.08 >/dev/null || { echo "cannot write the material"; exit 3; }
"$BIN" all --quick --models fq2 --measured m.binary --out R --quiet >/dev/null 2>"$T/err"
rc=$?
if [ "$rc" -eq 77 ]; then echo "no OpenCL device: skipped"; exit 77; fi
[ "$rc" -eq 0 ] && ok || { bad "all --quick --measured: exit $rc: $(head -c 400 "$T/err")"; echo "$pass passed, $fail failed"; exit 1; }

# 1. report gives again what all wrote; each section is the engine's page
cp -r R R2
"$BIN" report R2 >/dev/null 2>"$T/err" && ok || bad "report: $(cat "$T/err")"
cmp -s R/report.md R2/report.md && ok || bad "report differs from all's: $(diff R/report.md R2/report.md | head -5)"
python3 - R <<'PY' && ok || bad "a section of report.md is not its page"
import sys
d = sys.argv[1]
report = open(d + "/report.md").read()
for page, heading in (("frontier.md", "Which lobe to ship"), ("measured.md", "Measured materials")):
    text = open("%s/%s" % (d, page)).read()
    assert text and "## %s\n\n%s\n\n" % (heading, text) in report, page
PY

# 2. the pages' figures, written again from the layouts
python3 - R <<'PY' && ok || bad "frontier.md or measured.md does not show the layout's figures"
import json, sys
d = sys.argv[1]
fr = json.load(open(d + "/frontier.json"))
page = open(d + "/frontier.md").read()
ctx = fr["context"]
assert "the median over %d rounds over every model of each round's median of %d launches" % (ctx["rounds"], ctx["reps"]) in page
for m in fr["models"]:
    line = "| %s | %s | %s | %.3g | %.3g | %.4f%% | %.4f | %.4f%% | %.4f | " % (
        m["model"], m["kind"], "**yes**" if m["on_front"] else "", m["rate_uniform"]["median"],
        m["rate_varying"]["median"], 100 * m["n_2_1000"]["max_rel"], m["n_2_1000"]["max_abs"],
        100 * m["n_16_1000"]["max_rel"], m["n_16_1000"]["max_abs"])
    line += ("%.1f |" % m["psnr_db"]) if m["psnr_db"] is not None else "%s |" % m["psnr_reason"]
    assert line + "\n" in page, line
    assert "- `%s`: %s\n" % (m["model"], m["source"]) in page, m["source"]
front = [m["model"] for m in fr["models"] if m["on_front"]]
assert "The front: %s.\n" % ", ".join(front) in page, front
me = json.load(open(d + "/measured.json"))
page = open(d + "/measured.md").read()
for mat in me["materials"]:
    bp = mat["blinn_phong"]
    assert "### %s\n\n%d cells used (%d unmeasured, %d below the surface); device lookup ok at every cell.\n" % (
        mat["name"], mat["used_cells"], mat["unmeasured_cells"], mat["below_horizon_cells"]) in page, mat["name"]
    assert "| blinn-phong | n = %.5g, ks = %.5g, kd = %.5g | %.4g |\n" % (bp["n"], bp["ks"], bp["kd"], bp["rms"]) in page
    for lb in mat["lobes"]:
        line = "| %s | %.5g | %.5g | %.4g |\n" % (lb["model"], lb["err_measured"], lb["err_phong"], lb["ratio"])
        assert line in page, line
    assert "(measured_errors_m.png)" in page and "(measured_slice_m.png)" in page
PY

# 3. the previous versions' files (frontier/2: a rows member of the accuracy figures alone;
#    measured/1: no rows) read through their upgrade functions give the same report
python3 - R2 <<'PY'
import json, sys
d = sys.argv[1]
f = json.load(open(d + "/frontier.json"))
f["schema"] = "brdfbench.frontier/2"
f["rows"]["context"] = {}
for r in f["rows"]["rows"]:
    r["metrics"], r["attributes"] = r["metrics"][:5], {}
    r.pop("texts", None)
json.dump(f, open(d + "/frontier.json", "w"))
m = json.load(open(d + "/measured.json"))
m["schema"] = "brdfbench.measured/1"
del m["rows"]
json.dump(m, open(d + "/measured.json", "w"))
PY
"$BIN" report R2 >/dev/null 2>"$T/err" && ok || bad "report of the previous versions' files: $(cat "$T/err")"
cmp -s R/report.md R2/report.md && ok || bad "report from frontier/2 and measured/1 differs: $(diff R/report.md R2/report.md | head -5)"

# 4. the frontier's teapot pass: its own render.json, fq2's PSNR the one frontier.json shows
if [ -s R/frontier_teapot/render.json ]; then
    python3 - R <<'PY' && ok || bad "frontier.json's PSNR of fq2 is not frontier_teapot/render.json's"
import json, sys
d = sys.argv[1]
rd = json.load(open(d + "/frontier_teapot/render.json"))
psnr = [m["metrics"]["psnr_db"] for s in rd["scenes"] if s["scene"] == "teapot" for m in s["models"] if m["model"] == "fq2"]
fr = {m["model"]: m for m in json.load(open(d + "/frontier.json"))["models"]}
assert len(psnr) == 1 and psnr[0] is not None and fr["fq2"]["psnr_db"] == psnr[0], (psnr, fr["fq2"]["psnr_db"])
PY
else
    grep -q 'the teapot pass' R/frontier.md && ok || bad "no frontier_teapot/render.json and no reason in frontier.md"
fi

# 5. a section whose file is gone: report names the file and refuses (run.json records the part)
rm R2/measured.json
"$BIN" report R2 >/dev/null 2>"$T/err"
rc=$?
[ "$rc" -eq 2 ] && grep -q 'measured.json: missing (run.json records its part as done)' "$T/err" && ok \
    || bad "report without measured.json: exit $rc: $(cat "$T/err")"
# 6. a material whose file name holds '|' (legal in a file name; a table's cell separator): its
#    name is written with '?' there, as a control character is, so that measured.json stays
#    readable (its readers refuse a '|' in a name); the pictures' stem has '_' as before
mkdir -p pipe && cp m.binary 'pipe/a|b.binary'
"$BIN" measured 'pipe/a|b.binary' --fit-cells 2000 --out P --quiet >/dev/null 2>"$T/err" && ok || bad "measured a|b: $(cat "$T/err")"
"$BIN" rows P/measured.json --format json --output "$T/p.rows.json" 2>"$T/err" && ok || bad "rows of a|b: $(cat "$T/err")"
python3 - P/measured.json "$T/p.rows.json" <<'PY' && ok || bad "material a|b: its name or its rows"
import json, sys
d, rows = (json.load(open(p)) for p in sys.argv[1:3])
assert d["materials"][0]["name"] == "a?b", d["materials"][0]["name"]
assert rows["rows"][0]["keys"] == {"material": "a_b"} and rows["rows"][0]["texts"]["name"] == "a?b", rows["rows"][0]
PY
[ -s P/measured_errors_a_b.png ] && ok || bad "the picture of a|b is not measured_errors_a_b.png"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
