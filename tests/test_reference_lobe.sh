#!/usr/bin/env bash
# test_reference_lobe.sh - the lobe sweep (a lobe model f(c, n)) measured against a user lobe model
# named by accuracy --reference (a model file, user:NAME, the model's name): the reference's values
# come from the host in double (reference_source "host double values"). Each expectation is derived
# outside the program:
#   - k f against a user reference f (a second file written here, k = 1.25): delta = |k - 1| = 0.25
#     at every n (the relative error of k f against f is k - 1 wherever f > 0); Delta over the
#     attenuation zone is 0.25 f there, so at most 0.25 e^-0.511 (f's peak f(1, n) = 1); whole
#     Delta is 0.25 f(1, n) = 0.25 at x = 0;
#   - a model against itself as a reference file: every double figure 0 (the same function on both
#     sides), the device's figures at float rounding of a formula of five float operations (under
#     2^-20 of the peak 1), status ok;
#   - cq2's formula written as a user file and c^n written as a user file: the figures of that pair,
#     and of the built-in cq2 against the user c^n, equal those of the built-in cq2 against the
#     built-in phong (brdf_models.h's two formulas: the independent check) to 1e-9 relative, at the
#     same n; the same through the scalar, specialised builds (BRDFBENCH_SPECIALISE=1) and through
#     --model NAME=EXPR with --reference user:NAME, and with c^n as a GLSL file.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$T/pocl-cache}"
mkdir -p "$POCL_CACHE_DIR"
GRID=(--n-min 2 --n-max 120 --n-step 1 --samples 2048)

# value FILE PYTHON-EXPRESSION: the expression over r, the first lobe row of the JSON
value() {
    python3 -c "
import json, sys, math
d = json.load(open(sys.argv[1]))
r = [x for x in d['results'] if x.get('sweep') != 'hemisphere'][0]
print($2)" "$1"
}
# holds: testlib.sh (over this value, the first lobe row)
run() {   # run WHAT ARGS...: brdfbench with ARGS, exit 0 expected
    local what=$1
    shift
    "$BIN" "$@" >"$T/out" 2>"$T/err"
    local rc=$?
    if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed"; exit 77; fi
    [ $rc -eq 0 ] && ok || bad "$what: exit $rc: $(head -c 300 "$T/err")"
}

# f: cq2's lobe (n/2 (c - 1) + 1)^2, zero past its root (docs/definitions.md), written out here
cat >"$T/f.cl" <<'EOF2'
/* brdfbench-model
 * name: uf
 */
REAL uf(REAL c, REAL n)
{
    REAL b = 0.5f * n * (c - 1.0f) + 1.0f;
    return b > 0.0f ? b * b : 0.0f;
}
EOF2
sed 's/uf/ukf/g; s/return b > 0.0f ? b \* b/return b > 0.0f ? 1.25f * b * b/' "$T/f.cl" >"$T/kf.cl"
# c^n, the reference lobe of phong and blinn
cat >"$T/pw.cl" <<'EOF2'
/* brdfbench-model
 * name: upw
 */
REAL upw(REAL c, REAL n) { return pow(c, n); }
EOF2

# ---- k f against f ------------------------------------------------------------------------------
run "k f against f.cl" accuracy --model-file "$T/kf.cl" --reference "$T/f.cl" "${GRID[@]}" --json "$T/kf.json" \
    --csv "$T/kf.csv"
holds "$T/kf.json" "r['reference'] == 'uf' and r['reference_source'] == 'host double values' and r['status'] == 'ok'" \
    "k f against f: the reference named, read from the host's values, ok"
holds "$T/kf.json" "abs(r['epicentre']['max_rel'] - 0.25) < 1e-12" "k f against f: delta = |k - 1|"
holds "$T/kf.json" "r['attenuation']['max_abs'] <= 0.25 * math.exp(-0.511) * (1 + 1e-9)" \
    "k f against f: Delta (attenuation) at most 0.25 e^-0.511"
holds "$T/kf.json" "abs(r['whole']['max_abs'] - 0.25) < 1e-12 and r['whole']['at_x'] == 0" \
    "k f against f: whole Delta 0.25 f(1, n) at x = 0"
# every n: delta 0.25 (the CSV's per-n rows)
v=$(python3 -c "
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print(len(rows) == 119 and all(abs(float(x['epicentre_max_rel_fraction']) - 0.25) < 1e-12 for x in rows))" "$T/kf.csv")
[ "$v" = "True" ] && ok || bad "k f against f: delta 0.25 at each of the 119 n values: $v"

# ---- a model against itself as a reference file ------------------------------------------------
run "f against itself" accuracy --model-file "$T/f.cl" --reference "$T/f.cl" "${GRID[@]}" --json "$T/self.json"
holds "$T/self.json" "r['status'] == 'ok' and r['epicentre']['max_rel'] == 0 and r['whole']['max_abs'] == 0" \
    "f against itself: every double figure 0, status ok"
holds "$T/self.json" "r['epicentre']['grid_max_rel'] <= 2**-20 and r['whole']['grid_max_abs'] <= 2**-20" \
    "f against itself: the device's figures at float rounding"

# ---- cq2 against c^n: user files against the built-ins ------------------------------------------
run "cq2 against phong (built-ins)" accuracy --models cq2 --reference phong "${GRID[@]}" --json "$T/bb.json"
same() {   # same FILE WHAT: FILE's figures equal bb.json's (the built-ins')
    local v
    v=$(python3 -c "
import json, sys
def row(f):
    return [x for x in json.load(open(f))['results'] if x.get('sweep') != 'hemisphere'][0]
a, b = row(sys.argv[1]), row(sys.argv[2])
ok = a['status'] == 'ok' and a['reference_source'] == 'host double values'
for z, k in (('epicentre', 'max_rel'), ('attenuation', 'max_abs'), ('whole', 'max_abs')):
    ok = ok and abs(a[z][k] - b[z][k]) <= 1e-9 * b[z][k] and a[z]['at_n'] == b[z]['at_n']
print(ok)" "$1" "$T/bb.json" 2>&1)
    [ "$v" = "True" ] && ok || bad "$2: the figures differ from cq2 against phong: $v"
}
holds "$T/bb.json" "r['epicentre']['max_rel'] > 0.01 and r['reference_source'] == 'device code'" \
    "cq2 against phong: a figure to compare (the built-in reference on the device)"
run "uf against upw" accuracy --model-file "$T/f.cl" --reference "$T/pw.cl" "${GRID[@]}" --json "$T/uu.json"
same "$T/uu.json" "uf against upw.cl"
run "cq2 against upw" accuracy --models cq2 --reference "$T/pw.cl" "${GRID[@]}" --json "$T/bu.json"
same "$T/bu.json" "cq2 against upw.cl"
BRDFBENCH_SPECIALISE=1 run "uf against upw, specialised" accuracy --model-file "$T/f.cl" --reference "$T/pw.cl" \
    "${GRID[@]}" --json "$T/uu1.json"
same "$T/uu1.json" "uf against upw.cl, specialised builds"
BRDFBENCH_SPECIALISE=1 run "cq2 against upw, specialised" accuracy --models cq2 --reference "$T/pw.cl" "${GRID[@]}" \
    --json "$T/bu1.json"
same "$T/bu1.json" "cq2 against upw.cl, specialised builds"
# expressions on the command line, the reference by user:NAME
run "--model q --reference user:r" accuracy --model 'q=(0.5*n*(c-1)+1) > 0 ? (0.5*n*(c-1)+1)*(0.5*n*(c-1)+1) : 0' \
    --model 'r=pow(c, n)' --models q --reference user:r "${GRID[@]}" --json "$T/ex.json"
same "$T/ex.json" "q=EXPR against user:r"
# a GLSL lobe file as the reference (translated to the same user-model form)
cat >"$T/pw.glsl" <<'EOF2'
/* brdfbench-model
 * name: gpw
 */
float gpw(float c, float n) { return pow(c, n); }
EOF2
run "uf against gpw.glsl" accuracy --model-file "$T/f.cl" --reference "$T/pw.glsl" "${GRID[@]}" --json "$T/ug.json"
same "$T/ug.json" "uf against gpw.glsl"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
