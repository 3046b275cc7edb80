#!/usr/bin/env bash
# test_render_labels.sh - render's error figures say what they are, and say it alike on the
# terminal, in render.json and in the pictures' captions (recorded in render.json as drawn):
# max |model - reference| as absolute specular radiance, and the same maximum relative to the
# reference's peak radiance (the sphere grid's scale). The expected relations are computed
# here from render.json's own fields: the relative figure is max_abs / peak_reference, and the
# grid's scale is the largest of those over the models.
set -u
BIN=${BRDFBENCH:?BRDFBENCH must name the brdfbench binary}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$T/pocl-cache}"
mkdir -p "$POCL_CACHE_DIR"

"$BIN" render --scene spheres --models fvol,cq2 --size 128x96 --time-sizes none --out "$T/r" >"$T/out" 2>"$T/err"
rc=$?
if [ "$rc" -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed"; exit 77; fi
if [ "$rc" -ne 0 ]; then echo "FAIL render exited $rc: $(head -c 400 "$T/err")"; echo "0 passed, 1 failed"; exit 1; fi

python3 - "$T/out" "$T/r/render.json" <<'PY'
import json, re, sys
out, doc = open(sys.argv[1]).read(), json.load(open(sys.argv[2]))
passed = failed = 0
def check(cond, what):
    global passed, failed
    if cond:
        passed += 1
    else:
        failed += 1
        print("FAIL", what)
def near(printed, value):   # a figure printed with 3 significant digits
    return abs(float(printed) - value) <= 5e-3 * abs(value) + 1e-12
def g3(v):
    return "%.3g" % v

scene = [s for s in doc["scenes"] if s["scene"] == "spheres"][0]
worst = 0.0
for m in scene["models"]:
    mt, label = m["metrics"], m["model"]
    rel = mt["max_abs"] / mt["peak_reference"]          # relative to the reference's peak, computed here
    worst = max(worst, rel)
    unit = mt.get("max_abs_unit", "")
    check("absolute" in unit and "radiance" in unit, f"{label}: max_abs_unit says absolute radiance")
    check(abs(mt.get("max_abs_of_reference_peak", -1) - rel) <= 1e-12 * rel, f"{label}: JSON max_abs_of_reference_peak = max_abs / peak_reference")
    line = re.search(r"spheres\s+%s\s+max \|err\| (\S+)\s+radiance \((\S+) of ref peak (\S+)\)" % re.escape(label), out)
    check(line is not None, f"{label}: terminal line labels the absolute and the relative maximum")
    if line:
        check(near(line.group(1), mt["max_abs"]), f"{label}: printed radiance {line.group(1)} is JSON max_abs {mt['max_abs']}")
        check(near(line.group(2), rel), f"{label}: printed {line.group(2)} of ref peak is max_abs / peak_reference {rel}")
        check(near(line.group(3), mt["peak_reference"]), f"{label}: printed peak {line.group(3)} is peak_reference")
    cap = m.get("contact_sheet_caption", "")
    check(f"max |err| {g3(mt['max_abs'])} radiance" in cap and f"({g3(rel)} of the reference's peak)" in cap,
          f"{label}: contact sheet caption '{cap}' gives both figures, each named")
img = scene["image"]
check(abs(img.get("contact_sheet_error_scale_of_reference_peak", -1) - worst) <= 1e-6 * worst,
      "the grid's error scale is the largest max_abs / peak_reference of its rows")
gcap = img.get("contact_sheet_caption", "")
check(f"scale 0..{g3(worst)} of the peak" in gcap and "not radiance" in gcap,
      f"grid caption '{gcap}' names its scale as relative to the peak")
print(f"{passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
PY
