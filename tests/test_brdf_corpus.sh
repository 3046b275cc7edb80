#!/usr/bin/env bash
# test_brdf_corpus.sh - BRDF Explorer .brdf files of every shape the wdas/brdf corpus has
# (docs/user-models.md, "The BRDF Explorer corpus"), written here from their definitions: a full
# BRDF with roughness, a D term with m, Fresnel terms with f0 and ior, G terms with alphaG, a D
# term whose width is c, a diffuse term and a G term with no lobe parameter, a file with bool and
# color parameters, a file named phong.brdf (a built-in's name). They run in throughput and
# render with their defaults (exit 0, figures finite), and the terms run in accuracy against the
# built-in terms of their kind.
#
# Expected values come from identities, not from the program's output:
#  - a file whose BRDF is the exact Fresnel term (or the height-correlated Smith G) is its
#    reference, fresnel (smith-ggx-hc): its double figures are rounding (below 1e-9);
#  - a Schlick file with f0 takes f0 = ((n-1)/(n+1))^2 from the index n, which is the built-in
#    fresnel-schlick's formula; the separable-Smith file (alphaG = sqrt(2/(n+2))) is smith-ggx:
#    their figures equal those rows' to float-free digits (1e-9 relative), and are not 0;
#  - a Phong lobe written as pow(max(dot(R, V), 0), n) at lobe: psi is cos(psi)^n, the built-in
#    phong: error below 1e-9; without the key (theta_h, V at 2 theta_h) it is cos(2 theta_h)^n
#    against cos(theta_h)^n, far from it (above 10%): the key is honoured.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
export POCL_CACHE_DIR=${POCL_CACHE_DIR:-$T/pocl}
D=$T/files
mkdir -p "$D"

# ---- the files ----------------------------------------------------------------------------------
# A full Cook-Torrance with GGX, parameterised by the engines' roughness (alpha = roughness^2).
cat >"$D/full_rough.brdf" <<'EOF'
analytic
# full BRDF, roughness axis
::begin parameters
float roughness 0.01 1 0.5
float f0 0 1 0.04
::end parameters
::begin shader
const float PI = 3.14159265358979323846;
float sqr(float x) { return x*x; }
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    float nl = dot(N, L);
    float nv = dot(N, V);
    if (nl < 0 || nv < 0) return vec3(0);
    vec3 H = normalize(L + V);
    float a = roughness * roughness;
    float d = a*a / (PI * sqr(sqr(dot(N, H)) * (a*a - 1) + 1));
    float g = 4 * nl * nv / ((nl + sqrt(a*a + (1 - a*a)*nl*nl)) * (nv + sqrt(a*a + (1 - a*a)*nv*nv)));
    float f = f0 + (1 - f0) * pow(1 - dot(V, H), 5);
    return vec3(d * g * f / (4 * nl * nv));
}
::end shader
EOF
# A Beckmann D term with m.
cat >"$D/d_m.brdf" <<'EOF'
::begin parameters
float m 0.001 0.7 0.1
::end parameters
::begin shader
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    float t = dot(N, normalize(L + V));
    float t2 = t*t;
    return vec3(exp((t2 - 1) / (m*m*t2)) / (3.14159265358979 * m*m * t2*t2));
}
::end shader
EOF
# A D term whose width is called c (the lobe's own variable elsewhere: a parameter like others here).
cat >"$D/d_c.brdf" <<'EOF'
::begin parameters
float c 0.001 1 0.1
bool normalized 1
::end parameters
::begin shader
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    float ch = dot(N, normalize(L + V));
    float w = c*c / (ch*ch*(c*c - 1) + 1);
    float d = w*w;
    if (normalized) d /= 3.14159265358979 * c*c;
    return vec3(d);
}
::end shader
EOF
# Fresnel terms: Schlick with f0, the exact form with ior.
cat >"$D/f_f0.brdf" <<'EOF'
::begin parameters
float f0 0 1 0.04
::end parameters
::begin shader
/* brdfbench-model
 * reference: fresnel
 * lobe: theta_d
 */
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    float u = dot(L, normalize(L + V));
    return vec3(f0 + (1 - f0) * pow(1 - u, 5));
}
::end shader
EOF
cat >"$D/f_ior.brdf" <<'EOF'
::begin parameters
float ior 1 3 1.5
::end parameters
::begin shader
/* brdfbench-model
 * reference: fresnel
 * lobe: theta_d
 */
float exact(float c, float eta)
{
    float g = sqrt(eta*eta - 1 + c*c);
    float p = (g - c) / (g + c);
    float q = (c*(g + c) - 1) / (c*(g - c) + 1);
    return 0.5 * p*p * (1 + q*q);
}
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    return vec3(exact(dot(L, normalize(L + V)), ior));
}
::end shader
EOF
# G terms of GGX with alphaG: separable (with a bool, as the corpus' G files have) and
# height-correlated.
cat >"$D/g_sep.brdf" <<'EOF'
::begin parameters
float alphaG 0.001 1 0.1
bool includeInvNdotLNdotV 0
::end parameters
::begin shader
/* brdfbench-model
 * reference: smith-ggx-hc
 * lobe: theta_d
 */
float g1(float x, float a) { return 2 / (1 + sqrt(1 + a*a * (1 - x*x) / (x*x))); }
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    float g = g1(dot(N, L), alphaG) * g1(dot(N, V), alphaG);
    if (includeInvNdotLNdotV) g *= 1 / (dot(N, L) * dot(N, V));
    return vec3(g);
}
::end shader
EOF
cat >"$D/g_hc.brdf" <<'EOF'
::begin parameters
float alphaG 0.001 1 0.1
::end parameters
::begin shader
/* brdfbench-model
 * reference: smith-ggx-hc
 * lobe: theta_d
 */
float lambda(float x, float a) { return (-1 + sqrt(1 + a*a * (1 - x*x) / (x*x))) / 2; }
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    return vec3(1 / (1 + lambda(dot(N, L), alphaG) + lambda(dot(N, V), alphaG)));
}
::end shader
EOF
# A G term with no float at all, and a diffuse term whose only float is not a lobe parameter.
cat >"$D/g_none.brdf" <<'EOF'
::begin parameters
bool includeInvNdotLNdotV 0
::end parameters
::begin shader
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    float g = dot(N, L) * dot(N, V) / max(dot(N, L), dot(N, V));
    if (includeInvNdotLNdotV) g *= 1 / (dot(N, L) * dot(N, V));
    return vec3(g);
}
::end shader
EOF
cat >"$D/diffuse.brdf" <<'EOF'
::begin parameters
float albedo 0 1 0.8
::end parameters
::begin shader
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    return vec3(albedo / 3.14159265);
}
::end shader
EOF
# bool and color parameters (Ward-like, anisotropic widths that are no lobe parameter).
cat >"$D/boolcolor.brdf" <<'EOF'
::begin parameters
float alpha_x 0.01 1 0.15
float alpha_y 0.01 1 0.3
color Cs 1 0.9 0.8
color Cd 0.2 0.3 0.4
bool isotropic 0
::end parameters
::begin shader
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    vec3 H = normalize(L + V);
    float ax = alpha_x;
    float ay = isotropic ? alpha_x : alpha_y;
    float e = -((dot(H, X) / ax) * (dot(H, X) / ax) + (dot(H, Y) / ay) * (dot(H, Y) / ay)) / (dot(H, N) * dot(H, N));
    float spec = exp(e) / (4.0 * 3.14159265 * ax * ay * sqrt(dot(L, N) * dot(V, N)));
    return Cd / 3.14159265 + Cs * spec;
}
::end shader
EOF
# A file named phong.brdf: the Phong lobe pow(R.V, n), with lobe: psi; and the same lobe with no
# header (theta_h).
cat >"$D/phong.brdf" <<'EOF'
::begin parameters
float n 1 1000 100
bool divide_by_NdotL 0
::end parameters
::begin shader
/* brdfbench-model
 * lobe: psi
 */
vec3 reflect(vec3 I, vec3 N) { return 2*dot(I, N)*N - I; }
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    float v = pow(max(0, dot(reflect(L, N), V)), n);
    if (divide_by_NdotL) v = v / dot(N, L);
    return vec3(v);
}
::end shader
EOF
sed '/brdfbench-model/,/\*\//d' "$D/phong.brdf" >"$D/phong_th.brdf"

# ---- throughput: every file with its defaults ----------------------------------------------------
tp() {   # tp OUT FILES...: the smallest throughput run
    local out=$1
    shift
    local args=()
    for f in "$@"; do args+=(--model-file "$D/$f.brdf"); done
    "$BIN" throughput "${args[@]}" --reps 1 --min-time 0.0001 --variants default --n-modes uniform \
        --no-host-c --no-sweep --quiet --json "$T/$out.json" >"$T/out" 2>"$T/err"
}
tp tp1 full_rough d_m d_c f_f0 f_ior g_sep g_hc g_none
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "throughput of 8 .brdf files: exit $rc: $(head -c 400 "$T/err")"
tp tp2 diffuse boolcolor phong
rc=$?
[ $rc -eq 0 ] && ok || bad "throughput of diffuse, boolcolor, phong.brdf: exit $rc: $(head -c 400 "$T/err")"
# Every user model measured: status ok, values finite, a finite positive rate.
check_tp() {   # check_tp FILE MODELS...
    python3 - "$@" <<'EOF'
import json, math, sys
j = json.load(open(sys.argv[1]))
want = sys.argv[2:]
rows = {r["model"]: r for r in j["results"] if r["kind"] != "builtin"}
bad = [m for m in want if m not in rows]
for m, r in rows.items():
    e = r.get("evals_per_s") or {}
    if r["status"] != "ok" or r.get("values_finite") is not True or not (
            isinstance(e.get("median"), (int, float)) and math.isfinite(e["median"]) and e["median"] > 0):
        bad.append("%s: status %s, finite %s, rate %s" % (m, r["status"], r.get("values_finite"), e.get("median")))
sys.exit("; ".join(bad) if bad else 0)
EOF
}
check_tp "$T/tp1.json" full_rough d_m d_c f_f0 f_ior g_sep g_hc g_none && ok || bad "throughput rows of tp1"
# phong.brdf's model lives in its file's namespace; the built-in phong keeps its name.
check_tp "$T/tp2.json" diffuse boolcolor phong@phong.brdf && ok || bad "throughput rows of tp2 (phong@phong.brdf)"
"$BIN" throughput --model-file "$D/phong.brdf" --models phong,phong@phong.brdf --reps 1 --min-time 0.0001 \
    --variants default --n-modes uniform --no-host-c --no-sweep --quiet --json "$T/tp3.json" >"$T/out" 2>"$T/err" \
    && ok || bad "--models phong,phong@phong.brdf: $(head -c 400 "$T/err")"
python3 -c "
import json, sys
r = json.load(open(sys.argv[1]))['results']
f = {x['model']: x['formula'] for x in r}
sys.exit(0 if f.get('phong') == 'cos(psi)^n' and 'phong.brdf' in f.get('phong@phong.brdf', '') else str(f))
" "$T/tp3.json" && ok || bad "phong (built-in) and phong@phong.brdf (the file) measured side by side"
# A model with a plain name answers to NAME@FILE too.
"$BIN" throughput --model-file "$D/d_m.brdf" --models d_m@d_m.brdf --reps 1 --min-time 0.0001 --variants default \
    --n-modes uniform --no-host-c --no-sweep --quiet --json "$T/tp4.json" >"$T/out" 2>"$T/err" \
    && ok || bad "--models d_m@d_m.brdf: $(head -c 400 "$T/err")"
# A parameter named c is a model parameter like others: --models d_c:c=0.3 is accepted.
"$BIN" throughput --model-file "$D/d_c.brdf" --models d_c:c=0.3 --reps 1 --min-time 0.0001 --variants default \
    --n-modes uniform --no-host-c --no-sweep --quiet --json "$T/tp5.json" >"$T/out" 2>"$T/err" \
    && ok || bad "--models d_c:c=0.3: $(head -c 400 "$T/err")"

# ---- render: the smallest scene -----------------------------------------------------------------
"$BIN" render --model-file "$D/full_rough.brdf" --model-file "$D/g_none.brdf" --model-file "$D/boolcolor.brdf" \
    --model-file "$D/phong.brdf" --scene spheres --size 32x32 --time-sizes none --no-images --quiet \
    --out "$T/r" >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 0 ] && ok || bad "render of 4 .brdf files: exit $rc: $(head -c 400 "$T/err")"
python3 - "$T/r/render.json" <<'EOF' && ok || bad "render.json: every file's figures finite, its double check within bound"
import json, math, sys
j = json.load(open(sys.argv[1]))
want = {"full_rough", "g_none", "boolcolor", "phong@phong.brdf"}
seen, bad = set(), []
for sc in j["scenes"]:
    for m in sc["models"]:
        seen.add(m["model"].split(":")[0])
        mt = m["metrics"]
        for k in ("max_abs", "mean_abs", "rmse"):
            if not (isinstance(mt.get(k), (int, float)) and math.isfinite(mt[k])):
                bad.append("%s: %s = %s" % (m["model"], k, mt.get(k)))
        if m.get("double_reference_check", {}).get("within_bound") is not True:
            bad.append("%s: double check %s" % (m["model"], m.get("double_reference_check")))
if want - seen:
    bad.append("missing %s" % sorted(want - seen))
sys.exit("; ".join(bad) if bad else 0)
EOF

# ---- accuracy of the terms against the built-ins of their kind, over (angle, n) ------------------
# One run (each model is a kernel build): n in [1.1, 2.5] is the index of refraction of the Fresnel
# terms, alpha = sqrt(2/(n+2)) in [0.67, 0.80] for the G terms, the exponent of the Phong files.
"$BIN" accuracy --model-file "$D/f_f0.brdf" --model-file "$D/f_ior.brdf" --model-file "$D/g_sep.brdf" \
    --model-file "$D/g_hc.brdf" --model-file "$D/phong.brdf" --model-file "$D/phong_th.brdf" \
    --models f_f0,f_ior,fresnel-schlick,g_sep,g_hc,smith-ggx,phong@phong.brdf,phong_th \
    --n-min 1.1 --n-max 2.5 --n-step 0.2 --samples 256 --out "$T/a" >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 0 ] && ok || bad "accuracy of the term and Phong files: exit $rc: $(head -c 400 "$T/err")"
python3 - "$T/a/accuracy.json" <<'EOF' && ok || bad "term figures"
import json, sys
rows = {r["model"]: r for r in json.load(open(sys.argv[1]))["results"]}
bad = []
def fig(r, k):
    # a full BRDF without a lobe of its own is measured over the hemisphere (docs/definitions.md)
    z = r["hemisphere"] if r.get("sweep") == "hemisphere" else r
    return z["epicentre"]["max_rel"] if k == "rel" else z["whole"]["max_abs"]
# exact files against their references: rounding
for m, ref in (("f_ior", "fresnel"), ("g_hc", "smith-ggx-hc"), ("phong@phong.brdf", "phong")):
    r = rows[m]
    if r["reference"] != ref:
        bad.append("%s: reference %s, not %s" % (m, r["reference"], ref))
    for k in ("rel", "abs"):
        if not fig(r, k) < 1e-9:
            bad.append("%s against %s: %s figure %g, not rounding" % (m, ref, k, fig(r, k)))
# approximations written as files equal the built-in rows, and are not 0
for m, row in (("f_f0", "fresnel-schlick"), ("g_sep", "smith-ggx")):
    for k in ("rel", "abs"):
        a, b = fig(rows[m], k), fig(rows[row], k)
        if not (b > 1e-3 and abs(a - b) <= 1e-9 * b):
            bad.append("%s %s figure %.17g vs %s's %.17g" % (m, k, a, row, b))
# without lobe: psi the Phong file is cos(2 theta_h)^n against cos(theta_h)^n
if not fig(rows["phong_th"], "rel") > 0.1:
    bad.append("phong_th (theta_h) error %g: lobe: psi changed nothing" % fig(rows["phong_th"], "rel"))
sys.exit("; ".join(bad) if bad else 0)
EOF

# ---- a header key a .brdf file does not know: refused, naming the accepted ones ------------------
sed 's/ \* lobe: theta_d/ * foo: bar/' "$D/f_f0.brdf" >"$D/foo.brdf"
expect 2 "foo.brdf:7: unknown header key 'foo' \(accepted in a .brdf file: name, reference, lobe, description" \
    throughput --model-file "$D/foo.brdf" --no-host-c --out "$T/foo"
[ ! -e "$T/foo" ] && ok || bad "a refused file still wrote $T/foo"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
