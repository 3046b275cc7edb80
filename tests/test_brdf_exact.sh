#!/usr/bin/env bash
# test_brdf_exact.sh - .brdf files equal to a built-in, measured as shipped (issue 29): a bool of
# the file set with --param, and a width that the file names c placed on the axis by its role
# (--axis c:alpha). The files are written here in the shapes of BRDF Explorer's blinnphong and
# d_trowbridge_reitz. Expectations come from the formulas, not from the program:
#   - Blinn-Phong full form (N.H)^n with its bool divide_by_NdotL at 0 is blinn's c^n, c = N.H,
#     algebraically: max delta and max Delta are float rounding in double (bound 1e-9), status ok;
#   - with the bool at its default 1 it is c^n / N.L, whose relative error against c^n is
#     1/N.L - 1, far from 0 wherever N.L < 1/2 (bound: max delta > 1, i.e. 100%);
#   - Trowbridge-Reitz D c^2 / (pi ((N.H)^2 (c^2 - 1) + 1)^2) with c = alpha is ggx's
#     alpha^2 / (pi cos^4 (alpha^2 + tan^2)^2) (multiply out cos^4: (cos^2 alpha^2 + sin^2)^2 =
#     (cos^2 (alpha^2 - 1) + 1)^2), so --axis c:alpha with the reference's n = 2/alpha^2 - 2 gives
#     float-rounding figures, status ok; with --axis alpha, c stays at its default and delta is not 0;
#   - --param divide_by_NdotL=2 and --axis c:nosuch are refused with exit 2 and the accepted values,
#     and throughput / render refuse a bool out of 0 or 1 the same way.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$T/pocl-cache}"
mkdir -p "$POCL_CACHE_DIR"
GRID=(--hemisphere-grid 16x16x32 --axis-points 3)

# value / holds: testlib.sh (the first hemisphere row r and h = r['hemisphere'] of a JSON)

cat >"$T/bphong.brdf" <<'EOF2'
analytic
::begin parameters
float n 1 1000 50
bool divide_by_NdotL 1
::end parameters
::begin shader
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    float nh = max(dot(N, normalize(L + V)), 0.0);
    float f = pow(nh, n);
    if (divide_by_NdotL)
        f = f / dot(N, L);
    return vec3(f);
}
::end shader
EOF2

cat >"$T/dtr.brdf" <<'EOF2'
analytic
::begin parameters
float c 0.001 1 0.25
bool normalized 1
::end parameters
::begin shader
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    float t = dot(N, normalize(L + V));
    float q = t * t * (c * c - 1.0) + 1.0;
    float d = c * c / (q * q);
    if (normalized)
        d = d / 3.14159265358979;
    return vec3(d);
}
::end shader
EOF2

# ---- the bool at 0: blinn exactly ---------------------------------------------------------------
"$BIN" accuracy --model-file "$T/bphong.brdf" --reference blinn --param divide_by_NdotL=0 "${GRID[@]}" \
    --json "$T/b0.json" >"$T/out" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "bool 0: exit $rc: $(head -c 300 "$T/err")"
holds "$T/b0.json" "h['epicentre']['max_rel'] < 1e-9 and h['whole']['max_abs'] < 1e-9" \
    "bool 0: float-rounding figures against blinn"
holds "$T/b0.json" "r['status'] == 'ok' and r['label'] == 'bphong:divide_by_NdotL=0'" "bool 0: status ok, label"

# ---- the bool at its default 1: c^n / N.L ----------------------------------------------------------
"$BIN" accuracy --model-file "$T/bphong.brdf" --reference blinn "${GRID[@]}" --json "$T/b1.json" >"$T/out" \
    2>"$T/err" && ok || bad "bool 1: $(head -c 300 "$T/err")"
holds "$T/b1.json" "h['epicentre']['max_rel'] > 1" "bool 1: the 1/N.L factor shows (delta > 100%)"

# ---- Trowbridge-Reitz with its width c on the alpha axis ---------------------------------------------
"$BIN" accuracy --model-file "$T/dtr.brdf" --reference ggx --axis c:alpha "${GRID[@]}" --json "$T/tr.json" \
    >"$T/out" 2>"$T/err" && ok || bad "c:alpha: $(head -c 300 "$T/err")"
holds "$T/tr.json" "h['epicentre']['max_rel'] < 1e-9 and h['whole']['max_abs'] < 1e-9 * max(p['peak'] for p in h['per_p'])" \
    "c:alpha: float-rounding figures against ggx"
holds "$T/tr.json" "r['status'] == 'ok'" "c:alpha: status ok"
# the role with a range: c over [0.2, 0.6] is the axis
"$BIN" accuracy --model-file "$T/dtr.brdf" --reference ggx --axis c:alpha=0.2:0.6 "${GRID[@]}" \
    --json "$T/tr2.json" >"$T/out" 2>"$T/err" && ok || bad "c:alpha=0.2:0.6: $(head -c 300 "$T/err")"
holds "$T/tr2.json" "h['epicentre']['max_rel'] < 1e-9 and abs(h['per_p'][0]['p'] - 0.2) < 1e-6 and abs(h['per_p'][-1]['p'] - 0.6) < 1e-6" \
    "c:alpha=0.2:0.6: the axis' ends, exact figures"
# without the role, c stays at its default 0.25 while ggx's alpha moves: not equal
"$BIN" accuracy --model-file "$T/dtr.brdf" --reference ggx --axis alpha "${GRID[@]}" --json "$T/tr3.json" \
    >"$T/out" 2>"$T/err" && ok || bad "alpha without role: $(head -c 300 "$T/err")"
holds "$T/tr3.json" "h['epicentre']['max_rel'] > 0.1" "alpha without role: c at its default differs"

# ---- refusals ------------------------------------------------------------------------------------
expect_refused() {   # WHAT REGEX ARGS...
    local what=$1 re=$2
    shift 2
    "$BIN" "$@" >"$T/out" 2>"$T/err"
    local rc=$?
    if [ $rc -eq 2 ] && [ "$(wc -l <"$T/err")" -eq 1 ] && grep -Eq -- "$re" "$T/err"; then ok; else
        bad "$what: exit $rc: $(head -c 300 "$T/err")"; fi
}
expect_refused "--param bool=2" "--param: divide_by_NdotL=2 is out of range \(accepted: 0 or 1\)" \
    accuracy --model-file "$T/bphong.brdf" --reference blinn --param divide_by_NdotL=2
expect_refused "--axis c:nosuch" "the role 'nosuch' is unknown \(accepted roles: n, alpha, roughness, m" \
    accuracy --model-file "$T/dtr.brdf" --reference ggx --axis c:nosuch
expect_refused "--axis x:alpha" "has no parameter 'x' \(accepted: c, normalized\)" \
    accuracy --model-file "$T/dtr.brdf" --reference ggx --axis x:alpha
expect_refused "throughput --param bool=0.5" "--param divide_by_NdotL=0.5: .*must be an integer in \[0, 1\]" \
    throughput --model-file "$T/bphong.brdf" --param divide_by_NdotL=0.5
expect_refused "render --param nosuch" "--param: no listed model has a parameter 'nosuch'" \
    render --model-file "$T/bphong.brdf" --param nosuch=1

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
