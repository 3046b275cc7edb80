#!/usr/bin/env bash
# test_usermodel.sh - user models end to end: model files and --model expressions through
# the accuracy sweep and the gate command, their parameters, their double reference on the
# device (and its float fallback), compile errors in the user's own line numbers, and
# invalid model values reported with their count and first location.
#
# Expected values are closed forms of models chosen for them (f = k c^n has relative error
# |k - 1| everywhere) or identities (a user model that writes out cq2's formula has cq2's
# closed-form maximum), never the program's own output.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
F=$SRC/tests/test_usermodel_files


# 1. A model file with a parameter and an expression, in one accuracy run.
"$BIN" accuracy --model-file "$F/scaled.cl" --model 'half=0.5*pow(c, n)' \
    --models scaled:k=3,half --n-min 2 --n-max 50 --samples 256 --out "$T/a1" --quiet 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "accuracy with user models: exit $rc: $(cat "$T/err")"
# f = k c^n against c^n: delta = |k - 1| at every point; Delta = |k - 1| c^n, largest at x = 0
# (c = 1) over the whole range and at the epicentre's end x_e (c^n = e^-0.511) in the
# attenuation zone, which begins there.
check_json "$T/a1/accuracy.json" "closed-form figures of k c^n (k = 3 and 0.5)" <<'PY'
r = {x["label"]: x for x in d["results"]}
assert set(r) == {"scaled:k=3", "half"}, list(r)
for label, k in (("scaled:k=3", 3.0), ("half", 0.5)):
    x = r[label]
    assert x["status"] == "ok", x
    assert x["reference"] == "phong"
    assert abs(x["epicentre"]["max_rel"] - abs(k - 1)) < 1e-12, x["epicentre"]
    assert abs(x["whole"]["max_abs"] - abs(k - 1)) < 1e-12, x["whole"]
    assert abs(x["whole"]["at_x"]) < 1e-9, x["whole"]
    assert abs(x["attenuation"]["max_abs"] - abs(k - 1) * math.exp(-0.511)) < 1e-12, x["attenuation"]
    # The double reference ran on the device: its check against the float sweep holds.
    assert x["check"]["in_4th_digit_units"] < 0.05, x["check"]
    assert x["check"]["probe_max_diff_of_peak"] < 1e-5, x["check"]
    assert "reason" not in x, x
assert r["scaled:k=3"]["params"] == {"k": 3}
PY

# 2. Two parameters: myquad with a = 1/2, b = 0 is cq2's formula, whose maximum relative
#    error over n in [2, 50] is at n = 50 at the epicentre's end: 1 - (1 - 50u/2)^2 / e^-0.511
#    with u = 1 - exp(-0.511/50) (worked in test_cli_accuracy.sh as well).
"$BIN" accuracy --model-file "$F/quad.cl" --models myquad:a=0.5,b=0 --n-min 2 --n-max 50 --samples 256 \
    --out "$T/a2" --quiet 2>"$T/err" && ok || bad "accuracy myquad: $(cat "$T/err")"
check_json "$T/a2/accuracy.json" "myquad:a=0.5,b=0 has cq2's closed-form maximum" <<'PY'
x = d["results"][0]
assert x["label"] == "myquad:a=0.5,b=0" and x["params"] == {"a": 0.5, "b": 0}, x
u = -math.expm1(-0.511 / 50)
expect = 1 - (1 - 50 * u / 2) ** 2 / math.exp(-0.511)
assert abs(x["epicentre"]["max_rel"] - expect) < 1e-12, (x["epicentre"], expect)
assert x["epicentre"]["at_n"] == 50
PY

# 3. Without --models, only the user models run.
"$BIN" accuracy --model 'cube=c*c*c' --n-min 2 --n-max 10 --samples 64 --out "$T/a3" --quiet 2>"$T/err" \
    && ok || bad "accuracy --model only: $(cat "$T/err")"
check_json "$T/a3/accuracy.json" "only the user model runs when no --models is given" <<'PY'
assert [x["model"] for x in d["results"]] == ["cube"], d["results"]
PY

# 4. A text that is OpenCL C but not C (mul24, an OpenCL integer built-in) has its reference
#    on the device, and says so; where the device lacks cl_khr_fp64 (forced) that reference is
#    float, said so in the output; the figures keep float accuracy (|k - 1| = 0.5 to 1e-6).
BRDFBENCH_NO_FP64=1 "$BIN" accuracy --model 'half=0.5*pow(c, n)*mul24(1, 1)' --n-min 2 --n-max 20 --samples 64 \
    --out "$T/a4" >"$T/out" 2>"$T/err" && ok || bad "accuracy without fp64: $(cat "$T/err")"
grep -q "no cl_khr_fp64" "$T/out" && ok || bad "the table does not say that the reference is float"
grep -q "is not C.*mul24.*runs on the device" "$T/err" && ok || bad "the device fallback is not announced: $(cat "$T/err")"
check_json "$T/a4/accuracy.json" "float fallback is reported in accuracy.json" <<'PY'
x = d["results"][0]
assert "no cl_khr_fp64" in x["reason"], x
assert abs(x["epicentre"]["max_rel"] - 0.5) < 1e-6, x["epicentre"]
PY

# 5. Invalid values: sqrt(c - 1/2) is NaN exactly where c < 1/2 (x > pi/3, s = 1 - c > 1/2).
#    The epicentre (x <= x_e(2) = 0.685 < pi/3) is clean; the attenuation zone's samples
#    s_j = s_e (1/s_e)^(j/S), j = 1..S, s_e = 1 - exp(-0.511/n) (kernels/accuracy.cl), count
#    those past s = 1/2 (a sample within 1e-6 of it may fall either way in float: allowed per n).
"$BIN" accuracy --model 'sq=sqrt(c - 0.5)' --n-min 2 --n-max 12 --samples 256 --out "$T/a5" --quiet 2>"$T/err" \
    && ok || bad "accuracy of a NaN-producing model: $(cat "$T/err")"
check_json "$T/a5/accuracy.json" "NaN values are counted, with the first location" <<'PY'
x = d["results"][0]
S = 256
expect, slack = 0, 0
for n in range(2, 13):
    se = -math.expm1(-0.511 / n)
    for j in range(1, S + 1):
        sj = se * (1 / se) ** (j / S)
        if abs(sj - 0.5) < 1e-6: slack += 1
        elif sj > 0.5: expect += 1
assert x["status"] == "invalid_values", x["status"]
cnt = x["invalid"]["count"]
assert expect <= cnt <= expect + slack, (cnt, expect, slack)
assert x["invalid"]["at_n"] == 2 and x["invalid"]["at_x"] > math.pi / 3 - 1e-6, x["invalid"]
assert str(cnt) in x["reason"] and "NaN, Inf or negative" in x["reason"], x["reason"]
PY

# 6. A gate on a user model from a file named in the gates file (relative to it), and one on
#    an expression: closed-form values |k - 1| with bounds just either side.
mkdir -p "$T/g"
cp "$F/scaled.cl" "$T/g/"
cat >"$T/g/gates.json" <<'EOF'
{"gates": [
  {"model": "scaled:k=1.5", "model_file": "scaled.cl", "metric": "epicentre.max_rel",
   "n_min": 2, "n_max": 40, "samples": 256, "min": 0.4999999, "max": 0.5000001},
  {"model": "scaled:k=1.5", "model_file": "scaled.cl", "metric": "whole.max_abs",
   "n_min": 2, "n_max": 40, "samples": 256, "max": 0.4999},
  {"model": "quarter", "expression": "0.25 * pow(c, n)", "metric": "epicentre.max_rel",
   "n_min": 2, "n_max": 40, "samples": 256, "max": 0.7500001, "min": 0.7499999}
]}
EOF
"$BIN" gate "$T/g/gates.json" --json "$T/g/out.json" --quiet >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 1 ] && ok || bad "gate on user models: exit $rc (expected 1: one bound below 0.5): $(cat "$T/err")"
check_json "$T/g/out.json" "user-model gates judged on closed forms" <<'PY'
g = d["gates"]
assert [x["status"] for x in g] == ["pass", "fail", "pass"], [(x["status"], x.get("reason")) for x in g]
assert all(x["user_model"] for x in g)
assert abs(g[0]["measured"] - 0.5) < 1e-12 and abs(g[1]["measured"] - 0.5) < 1e-12
assert abs(g[2]["measured"] - 0.75) < 1e-12
assert d["summary"]["sweeps"] == 2, d["summary"]
PY

# 7. Render: shade.cl built with the user model. f = k c^n against c^n: with k = 1 the images are
#    identical (max 0), with k = 2 the difference is the reference itself, so its largest
#    value is the reference's peak; the double reference (on the device) checks out.
"$BIN" render --model-file "$F/scaled.cl" --models scaled:k=1,scaled:k=2 --scene spheres --size 96x64 \
    --time-sizes none --no-images --quiet --out "$T/r1" >"$T/out" 2>"$T/err" && ok || bad "render with a user model: $(cat "$T/err")"
check_json "$T/r1/render.json" "render of k c^n: identity figures" <<'PY'
ms = {m["model"]: m for m in d["scenes"][0]["models"]}
one, two = ms["scaled:k=1"], ms["scaled:k=2"]
assert one["family"] == "user" and one["reference"] == "phong"
assert one["metrics"]["max_abs"] == 0, one["metrics"]
p = two["metrics"]["peak_reference"]
assert p > 0 and abs(two["metrics"]["max_abs"] - p) <= 1e-6 * p, two["metrics"]
assert one["double_reference_check"]["within_bound"] and two["double_reference_check"]["within_bound"]
PY

# 8. The main job with a user model (quick grids): it joins the sweep, the heatmaps (field.cl
#    built with it) and the images. f = 2 c^n: relative error exactly 1 in every cell.
"$BIN" all --quick --model-file "$F/scaled.cl" --models fq2,scaled:k=2 --out "$T/all" >"$T/out" 2>"$T/err" \
    && ok || bad "all with a user model: $(tail -5 "$T/err")"
[ -s "$T/all/heatmap_scaled_k2.png" ] && ok || bad "all: no heatmap of the user model"
check_json "$T/all/frontier.json" "the frontier of all --models with a user model" <<'PY'
assert [m["model"] for m in d["models"]] == ["fq2", "scaled:k=2"], [m["model"] for m in d["models"]]
PY
check_json "$T/all/field_scaled_k2.json" "the user model's error field" <<'PY'
assert d["model"] == "scaled:k=2" and d["reference"] == "phong"
assert d["check"]["max_rel_diff"] < 1e-6, d["check"]
# (2r - r) / r = 1 in every cell, and exactly so in float (2r and 2r - r are exact)
cells = d["grid"]["rows"] * d["grid"]["cols"]
assert len(d["epicentre_rel"]) == cells and all(v == 1 for v in d["epicentre_rel"]), d["epicentre_rel"][:8]
PY

# 9. Throughput: throughput.cl built with the user model; its rate is measured and its values
#    agree with its double reference (the model is fq2's formula at a = 0.448, b = 0.099).
"$BIN" throughput --model-file "$F/quad.cl" --models myquad --reps 1 --min-time 0.002 --variants default \
    --n-modes uniform --no-sweep --no-host-c --quiet --out "$T/tp" 2>"$T/err" && ok || bad "throughput with a user model: $(tail -3 "$T/err")"
check_json "$T/tp/throughput.json" "the user model measured by throughput" <<'PY'
r = [x for x in d["results"] if x["model"] == "myquad"]
assert len(r) == 1, [x["model"] for x in d["results"]]
r = r[0]
assert r["status"] == "ok", r
# the ratio to pow() is this median over the median of the pow() row, measured in the same run
p = [x for x in d["results"] if x["label"] == "pow" and x["n_mode"] == r["n_mode"] and x["variant"] == r["variant"]][0]
assert abs(r["ratio_to_reference"] - r["evals_per_s"]["median"] / p["evals_per_s"]["median"]) <= 1e-9 * r["ratio_to_reference"], r
assert r["accuracy"]["status"] == "ok" and r["accuracy"]["max_diff_of_peak"] < 1e-5, r["accuracy"]
PY

# 10. Errors: the build log in the user's own line numbers, exit 2.
expect 2 "bad_syntax.cl:6:[0-9]+: .*expected ';'" accuracy --model-file "$F/bad_syntax.cl" --n-max 4 --samples 16 --out "$T/e1"
[ ! -e "$T/e1/accuracy.json" ] && ok || bad "a failed build wrote results"
# 'q' is the 13th character of the expression.
expect 2 "--model e1:1:13: .*undeclared identifier 'q'" accuracy --model 'e1=pow(c, n) * q' --n-max 4 --out "$T/e2"
cp "$F/bad_syntax.cl" "$T/g/bad_syntax.cl"   # a gates file names model files beside it
cat >"$T/g/broken.json" <<EOF
{"gates": [{"model": "broken", "model_file": "bad_syntax.cl", "metric": "epicentre.max_rel", "max": 1}]}
EOF
expect 2 "bad_syntax.cl:6:" gate "$T/g/broken.json"
expect 2 "bad_syntax.cl:6:" render --model-file "$F/bad_syntax.cl" --scene spheres --size 32x32 --time-sizes none --out "$T/e3"

# 11. docs/user-models.md's one-line example: the command it shows gives the figures it states.
#     The expression is quad:a=0.45,b=0 written out, so both rows agree; the figures are also
#     worked here in double (a grid search refined by golden sections, per n).
DOC=$SRC/docs/user-models.md
EXPR='fmax(0.45*n*(c-1)+1,0)*fmax(0.45*n*(c-1)+1,0)'
grep -qF "brdfbench accuracy --model 'sq=$EXPR' --n-min 16" "$DOC" && ok || bad "the doc's example is not the command tested here"
"$BIN" accuracy --model "sq=$EXPR" --models sq,quad:a=0.45,b=0 --n-min 16 --out "$T/doc" --quiet 2>"$T/err" \
    && ok || bad "the doc's example: $(cat "$T/err")"
python3 - "$T/doc/accuracy.json" "$DOC" <<'PY' && ok || bad "the doc's example gives other figures than the doc states"
import json, math, re, sys
d = json.load(open(sys.argv[1]))
doc = open(sys.argv[2]).read()
sq, quad = d["results"]
for zone, key in (("epicentre", "max_rel"), ("attenuation", "max_abs"), ("whole", "max_abs")):
    a, b = sq[zone], quad[zone]
    assert abs(a[key] - b[key]) <= 1e-12 * b[key] and a["at_n"] == b["at_n"], (zone, a, b)
def f(c, n):
    b = max(0.45 * n * (c - 1) + 1, 0.0)
    return b * b
def xe(n): return math.acos(math.exp(-0.511 / n))
def maximum(g, lo, hi, steps=4000):
    xs = [lo + (hi - lo) * i / steps for i in range(steps + 1)]
    i = max(range(len(xs)), key=lambda k: g(xs[k]))
    a, b = xs[max(i - 1, 0)], xs[min(i + 1, steps)]
    r = (math.sqrt(5) - 1) / 2
    for _ in range(100):
        x1, x2 = b - r * (b - a), a + r * (b - a)
        if g(x1) > g(x2): b = x2
        else: a = x1
    return max(g(xs[i]), g((a + b) / 2))
rel = lambda n: maximum(lambda x: abs(f(math.cos(x), n) / math.cos(x) ** n - 1), 0.0, xe(n))
ab = lambda n: maximum(lambda x: abs(f(math.cos(x), n) - math.cos(x) ** n), xe(n), math.pi / 2, 40000)
e, t = sq["epicentre"], sq["attenuation"]
assert e["at_n"] == 16 and t["at_n"] == 1000, (e, t)
assert abs(e["max_rel"] - rel(16)) < 1e-9, (e, rel(16))
assert abs(t["max_abs"] - ab(1000)) < 1e-9, (t, ab(1000))
# the maxima over n are where the run puts them (a sample of the grid)
for n in (17, 20, 32, 64, 100, 250, 500, 999):
    assert rel(n) <= e["max_rel"] + 1e-12 and ab(n) <= t["max_abs"] + 1e-12, n
# the doc states them to 4 significant digits
m = re.search(r"max δ of ([0-9.]+)% in the epicentre \(at n = (\d+), x = ([0-9.]+) rad\) and a max Δ of\s+([0-9.]+) in the attenuation zone \(at n = (\d+), x = ([0-9.]+) rad\)", doc)
assert m, "no figures in the doc"
assert m.group(1) == "%.4g" % (100 * e["max_rel"]) and int(m.group(2)) == 16, (m.groups(), e)
assert float(m.group(3)) == round(e["at_x"], 4), (m.groups(), e)
assert m.group(4) == "%.4f" % t["max_abs"] and int(m.group(5)) == 1000, (m.groups(), t)
assert float(m.group(6)) == round(t["at_x"], 4), (m.groups(), t)
PY

# 12. native_* functions compile in every build; in the reference they are exact, so a model
#     that is the Phong lobe through native_powr has the Phong lobe's figures (0, to rounding).
"$BIN" accuracy --model 'np=native_powr(c, n)' --n-max 50 --samples 256 --out "$T/np" --quiet 2>"$T/err" \
    && ok || bad "a model with native_powr: $(cat "$T/err")"
check_json "$T/np/accuracy.json" "native_powr is exact in the reference" <<'PY'
x = d["results"][0]
assert x["status"] == "ok", x
assert x["epicentre"]["max_rel"] < 1e-13 and x["whole"]["max_abs"] < 1e-13, x
PY

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
