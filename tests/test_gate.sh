#!/usr/bin/env bash
# test_gate.sh - `brdfbench gate`: gates pass and fail on values derived here independently
# (a brute-force maximisation in double, closed forms), the exit codes, the sweep plan (a
# narrower gate reads its figure off a wider sweep), JUnit XML, the JSON result, and
# --baseline regressions.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init

# py WHAT CODE ARGS...: runs python CODE with sys.argv[1:] = ARGS; counts its success.
py() {
    local what=$1 code=$2
    shift 2
    python3 -c "$code" "$@" && ok || bad "$what"
}

# Independent values, in double:
# - fq2's max relative error over the epicentre, n = 2..1000: each n sampled at 200 points of
#   [0, x_e(n)] and the best one refined by golden section;
# - cq2's relative error at n = 1000 at the epicentre's end x_e, c^n = e^-0.511 (closed form): a
#   lower bound of its maximum over the range;
# - fq2n's energy 2 pi int_0^1 f c dc in closed form (a polynomial of u = c - 1 integrated
#   from u0 = max(-1, -1/k) to 0, k = 0.448 n + 0.099), its largest |E - 1| over n = 2..1000.
python3 - >"$T/expected" <<'PY'
import math
def fq2(c, n):
    b = (0.448 * n + 0.099) * (c - 1) + 1
    return b * b if b > 0 else 0.0
def delta(x, n):
    c = math.cos(x); r = math.exp(n * math.log(c))
    return abs(fq2(c, n) - r) / r
best = 0.0
g = (math.sqrt(5) - 1) / 2
for n in range(2, 1001):
    xe = math.acos(math.exp(-0.511 / n))
    xs = [xe * i / 199 for i in range(200)]
    vs = [delta(x, n) for x in xs]
    i = max(range(200), key=lambda j: vs[j])
    a, b = xs[max(i - 1, 0)], xs[min(i + 1, 199)]
    m = max(vs)
    for _ in range(80):
        c1, c2 = b - g * (b - a), a + g * (b - a)
        if delta(c1, n) > delta(c2, n): b = c2
        else: a = c1
    best = max(best, m, delta((a + b) / 2, n))
print("fq2_epi", repr(best))
n = 1000
u = -math.expm1(-0.511 / n)
print("cq2_lower", repr(1 - (1 - n * u / 2) ** 2 / math.exp(-0.511)))
def F(u, k):   # antiderivative of (1 + k u)^2 (1 + u)
    return u*u/2 + u + 2*k*u**3/3 + k*u*u + k*k*u**4/4 + k*k*u**3/3
dev, at = 0.0, 0
for n in range(2, 1001):
    k = 0.448 * n + 0.099
    u0 = max(-1.0, -1.0 / k)
    e = 2 * math.pi * 0.214 * (0.807 + n) * (F(0, k) - F(u0, k))
    if abs(e - 1) > dev: dev, at = abs(e - 1), n
print("fq2n_energy", repr(dev), at)
PY
val() { awk -v k="$1" '$1 == k { print $2 }' "$T/expected"; }
FQ2=$(val fq2_epi) CQ2L=$(val cq2_lower) FQ2N=$(val fq2n_energy)
[ -n "$FQ2" ] && [ -n "$CQ2L" ] && [ -n "$FQ2N" ] && ok || bad "independent values were not computed"
hi() { python3 -c "import sys; print(repr(float(sys.argv[1]) * (1 + float(sys.argv[2]))))" "$1" "$2"; }
lo() { python3 -c "import sys; print(repr(float(sys.argv[1]) * (1 - float(sys.argv[2]))))" "$1" "$2"; }

# 1. The issue's shape passes, and the figure is the brute-force maximum.
cat >"$T/shape.json" <<'EOF'
{"gates":[{"model":"fq2","metric":"epicentre.max_rel","n_min":2,"n_max":1000,"max":0.0126}]}
EOF
"$BIN" gate "$T/shape.json" --json "$T/shape.out.json" --junit "$T/shape.xml" >"$T/out" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "the issue's example gate: exit $rc: $(cat "$T/err")"
grep -qE '^PASS  fq2 epicentre.max_rel n=\[2,1000\]: measured 0.01256[0-9]* .*bound max 0.0126; margin \+' "$T/out" \
    && ok || bad "the PASS line: $(cat "$T/out")"
py "fq2's figure is the brute-force maximum" '
import json, sys
g = json.load(open(sys.argv[1]))["gates"][0]
v = float(sys.argv[2])
assert abs(g["measured"] - v) <= 1e-9 * v, (g["measured"], v)
assert g["status"] == "pass" and abs(g["margin"] - (0.0126 - g["measured"])) < 1e-15
' "$T/shape.out.json" "$FQ2"

# 2. Bounds just either side of the independent values: they gate (exit 1 on any failure).
cat >"$T/sides.json" <<EOF
{"description": "bounds either side of independently derived figures",
 "gates": [
  {"name": "fq2 below max", "model": "fq2", "metric": "epicentre.max_rel", "max": $(hi "$FQ2" 1e-6)},
  {"name": "fq2 above max", "model": "fq2", "metric": "epicentre.max_rel", "max": $(lo "$FQ2" 1e-6)},
  {"name": "fq2 below min", "model": "fq2", "metric": "epicentre.max_rel", "min": $(hi "$FQ2" 1e-6), "max": 1},
  {"name": "cq2 above its lower bound", "model": "cq2", "metric": "epicentre.max_rel", "max": $(lo "$CQ2L" 1e-3)},
  {"name": "fq2n energy", "model": "fq2n", "metric": "energy.max_abs_dev",
   "min": $(lo "$FQ2N" 1e-7), "max": $(hi "$FQ2N" 1e-7)},
  {"name": "phongn energy", "model": "phongn", "metric": "energy.max_abs_dev", "max": 1e-9},
  {"name": "fq2 attenuation on 16..1000", "model": "fq2", "metric": "attenuation.max_abs", "n_min": 16, "max": 1},
  {"name": "fq2 whole on 2..500", "model": "fq2", "metric": "whole.max_abs", "n_max": 500, "max": 1},
  {"name": "fq2 off the lattice", "model": "fq2", "metric": "whole.max_abs", "n_min": 2.5, "n_max": 10, "max": 1},
  {"name": "cq2 invalid values", "model": "cq2", "metric": "invalid.count", "max": 0}
 ]}
EOF
"$BIN" gate "$T/sides.json" --json "$T/sides.out.json" --junit "$T/sides.xml" >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 1 ] && ok || bad "a failing gate must exit 1, got $rc: $(cat "$T/err")"
py "each gate judged on the independent values" '
import json, sys
d = json.load(open(sys.argv[1]))
st = {g["name"]: g["status"] for g in d["gates"]}
expect = {"fq2 below max": "pass", "fq2 above max": "fail", "fq2 below min": "fail",
          "cq2 above its lower bound": "fail", "fq2n energy": "pass", "phongn energy": "pass",
          "fq2 attenuation on 16..1000": "pass", "fq2 whole on 2..500": "pass",
          "fq2 off the lattice": "pass", "cq2 invalid values": "pass"}
assert st == expect, st
g = {x["name"]: x for x in d["gates"]}
assert g["fq2n energy"]["at_n"] == int(sys.argv[2]), g["fq2n energy"]
# (cq2 attains its maximum at that very point: equal up to rounding)
assert g["cq2 above its lower bound"]["measured"] >= float(sys.argv[3]) * (1 - 1e-12)
assert "above max" in g["fq2 above max"]["reason"] and "below min" in g["fq2 below min"]["reason"]
# fq2 on 2..1000 (three gates), on 16..1000 and on 2..500 share one sweep; 2.5..10 is off its
# lattice and gets its own; cq2 is one more; energies need none.
assert d["summary"] == {"gates": 10, "passed": 7, "failed": 3, "sweeps": 3}, d["summary"]
assert d["description"].startswith("bounds either side")
' "$T/sides.out.json" "$(awk '$1 == "fq2n_energy" { print $3 }' "$T/expected")" "$CQ2L"
[ "$(grep -c '^FAIL  ' "$T/out")" -eq 3 ] && [ "$(grep -c '^PASS  ' "$T/out")" -eq 7 ] && ok \
    || bad "printed PASS/FAIL lines: $(cat "$T/out")"
grep -qE '^10 gates: 7 passed, 3 failed' "$T/out" && ok || bad "summary line: $(tail -1 "$T/out")"

# 2b. albedo.max (the device quadrature of host/measure/energy/energy.h, stated tolerance 2e-5): for a lobe
#    around the mirror direction the albedo is largest at normal incidence (the horizon clips
#    the lobe elsewhere), where it is 2 pi int_0^1 f c dc: exactly 1 for phongn, and for fq2n
#    the closed form above. n = 2, 113, ..., 893, 1000.
python3 - >"$T/albedo_expected" <<'PY'
import math
def F(u, k): return u*u/2 + u + 2*k*u**3/3 + k*u*u + k*k*u**4/4 + k*k*u**3/3
ns = [2 + 111 * i for i in range(9)] + [1000]
def E(n):
    k = 0.448 * n + 0.099
    return 2 * math.pi * 0.214 * (0.807 + n) * (F(0, k) - F(max(-1.0, -1.0 / k), k))
print(repr(max(E(n) for n in ns)))
PY
A=$(cat "$T/albedo_expected")
cat >"$T/albedo.json" <<EOF
{"gates": [
  {"model": "phongn", "metric": "albedo.max", "n_step": 111, "min": $(lo 1 2e-5), "max": $(hi 1 2e-5)},
  {"model": "fq2n", "metric": "albedo.max", "n_step": 111, "min": $(lo "$A" 2e-5), "max": $(hi "$A" 2e-5)}
]}
EOF
"$BIN" gate "$T/albedo.json" --json "$T/albedo.out.json" --quiet >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 0 ] && ok || bad "albedo gates: exit $rc: $(cat "$T/out" "$T/err")"
py "albedo.max at normal incidence" '
import json, sys
for g in json.load(open(sys.argv[1]))["gates"]:
    assert g["status"] == "pass" and g["at_x"] == 0, g
' "$T/albedo.out.json"

# 3. JUnit XML that a CI system can render: well-formed, one testcase per gate, <failure>
#    exactly on the failing ones.
py "JUnit XML" '
import sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
assert root.tag == "testsuites" and root.get("tests") == "10" and root.get("failures") == "3"
suite = root.find("testsuite")
cases = suite.findall("testcase")
assert len(cases) == 10
failing = sorted(c.get("name") for c in cases if c.find("failure") is not None)
assert failing == ["cq2 above its lower bound", "fq2 above max", "fq2 below min"], failing
for c in cases:
    f = c.find("failure")
    if f is not None: assert f.get("type") == "bound" and f.get("message")
    assert c.get("classname").startswith("brdfbench.gate.")
' "$T/sides.xml"
if command -v xmllint >/dev/null; then xmllint --noout "$T/shape.xml" "$T/sides.xml" && ok || bad "xmllint"; fi

# 4. --baseline: against an accuracy.json of the same models and grid, nothing regresses;
#    a baseline whose figure is 1% lower makes the same gate fail as a regression, unless
#    the tolerance allows 2%. A gate with no matching entry is reported, not failed.
"$BIN" accuracy --models fq2,cq2 --n-min 2 --n-max 1000 --out "$T/base" --quiet 2>"$T/err" \
    && ok || bad "baseline accuracy run: $(cat "$T/err")"
cat >"$T/base.json" <<'EOF'
{"gates":[{"model":"fq2","metric":"epicentre.max_rel","max":0.0126},
          {"model":"fq2","metric":"attenuation.max_abs","n_min":16,"max":1}]}
EOF
"$BIN" gate "$T/base.json" --baseline "$T/base" --json "$T/b1.json" --quiet >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 0 ] && ok || bad "gate against its own baseline: exit $rc: $(cat "$T/out" "$T/err")"
py "baseline compared" '
import json, sys
g = json.load(open(sys.argv[1]))["gates"]
assert g[0]["baseline"]["status"] == "ok" and abs(g[0]["baseline"]["change_rel"]) < 1e-9, g[0]
assert g[1]["baseline"]["status"] == "missing" and g[1]["status"] == "pass", g[1]
' "$T/b1.json"
python3 - "$T/base/accuracy.json" "$T/lower.json" <<'PY' && ok || bad "making the lowered baseline"
import json, sys
d = json.load(open(sys.argv[1]))
for r in d["results"]:
    if r["label"] == "fq2": r["epicentre"]["max_rel"] *= 0.99
# the rows member, what gate --baseline reads, says the same
for r in d["rows"]["rows"]:
    for m in r["metrics"]:
        if r["keys"]["label"] == "fq2" and m["name"] == "epicentre.max_rel": m["value"] *= 0.99
json.dump(d, open(sys.argv[2], "w"))
PY
"$BIN" gate "$T/base.json" --baseline "$T/lower.json" --json "$T/b2.json" --junit "$T/b2.xml" --quiet >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 1 ] && ok || bad "a regression must exit 1, got $rc"
grep -qE '^FAIL  fq2 epicentre.max_rel .*regression: .*\(\+1\.0[0-9]*%, tolerance 0\.1%\)' "$T/out" && ok \
    || bad "regression line: $(cat "$T/out")"
py "regression in JSON and JUnit" '
import json, sys, xml.etree.ElementTree as ET
g = json.load(open(sys.argv[1]))["gates"][0]
assert g["status"] == "fail" and g["baseline"]["status"] == "regression", g
assert abs(g["baseline"]["change_rel"] - (1 / 0.99 - 1)) < 1e-9, g["baseline"]
f = ET.parse(sys.argv[2]).getroot().find("testsuite").find("testcase").find("failure")
assert f is not None and f.get("type") == "regression"
' "$T/b2.json" "$T/b2.xml"
"$BIN" gate "$T/base.json" --baseline "$T/lower.json" --tolerance 0.02 --quiet >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 0 ] && ok || bad "a 1% change within a 2% tolerance must pass, got $rc: $(cat "$T/out")"

# 5. The documented example (tests/gates/example.json, every kind of gate; its bounds are
#    loose or closed forms: f = 0.9 c^n has relative error 0.1) runs and passes.
"$BIN" gate "$SRC/tests/gates/example.json" >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 0 ] && [ "$(grep -c '^PASS  ' "$T/out")" -eq 8 ] && ok || bad "example.json: exit $rc: $(cat "$T/out" "$T/err")"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
