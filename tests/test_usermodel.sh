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
jsoncheck usermodel_closed_form_figures_k_c_n "$T/a1/accuracy.json" && ok || bad "closed-form figures of k c^n (k = 3 and 0.5)"

# 2. Two parameters: myquad with a = 1/2, b = 0 is cq2's formula, whose maximum relative
#    error over n in [2, 50] is at n = 50 at the epicentre's end: 1 - (1 - 50u/2)^2 / e^-0.511
#    with u = 1 - exp(-0.511/50) (worked in test_cli_accuracy.sh as well).
"$BIN" accuracy --model-file "$F/quad.cl" --models myquad:a=0.5,b=0 --n-min 2 --n-max 50 --samples 256 \
    --out "$T/a2" --quiet 2>"$T/err" && ok || bad "accuracy myquad: $(cat "$T/err")"
jsoncheck usermodel_myquad_cq2_closed_form "$T/a2/accuracy.json" && ok || bad "myquad:a=0.5,b=0 has cq2's closed-form maximum"

# 3. Without --models, only the user models run.
"$BIN" accuracy --model 'cube=c*c*c' --n-min 2 --n-max 10 --samples 64 --out "$T/a3" --quiet 2>"$T/err" \
    && ok || bad "accuracy --model only: $(cat "$T/err")"
jsoncheck usermodel_only_user_model_runs "$T/a3/accuracy.json" && ok || bad "only the user model runs when no --models is given"

# 4. A text that is OpenCL C but not C (mul24, an OpenCL integer built-in) has its reference
#    on the device, and says so; where the device lacks cl_khr_fp64 (forced) that reference is
#    float, said so in the output; the figures keep float accuracy (|k - 1| = 0.5 to 1e-6).
BRDFBENCH_NO_FP64=1 "$BIN" accuracy --model 'half=0.5*pow(c, n)*mul24(1, 1)' --n-min 2 --n-max 20 --samples 64 \
    --out "$T/a4" >"$T/out" 2>"$T/err" && ok || bad "accuracy without fp64: $(cat "$T/err")"
grep -q "no cl_khr_fp64" "$T/out" && ok || bad "the table does not say that the reference is float"
grep -q "is not C.*mul24.*runs on the device" "$T/err" && ok || bad "the device fallback is not announced: $(cat "$T/err")"
jsoncheck usermodel_float_fallback_reported_accuracy "$T/a4/accuracy.json" && ok || bad "float fallback is reported in accuracy.json"

# 5. Invalid values: sqrt(c - 1/2) is NaN exactly where c < 1/2 (x > pi/3, s = 1 - c > 1/2).
#    The epicentre (x <= x_e(2) = 0.685 < pi/3) is clean; the attenuation zone's samples
#    s_j = s_e (1/s_e)^(j/S), j = 1..S, s_e = 1 - exp(-0.511/n) (kernels/accuracy.cl), count
#    those past s = 1/2 (a sample within 1e-6 of it may fall either way in float: allowed per n).
"$BIN" accuracy --model 'sq=sqrt(c - 0.5)' --n-min 2 --n-max 12 --samples 256 --out "$T/a5" --quiet 2>"$T/err" \
    && ok || bad "accuracy of a NaN-producing model: $(cat "$T/err")"
jsoncheck usermodel_nan_values_counted "$T/a5/accuracy.json" && ok || bad "NaN values are counted, with the first location"

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
jsoncheck usermodel_gates_on_closed_forms "$T/g/out.json" && ok || bad "user-model gates judged on closed forms"

# 7. Render: shade.cl built with the user model. f = k c^n against c^n: with k = 1 the images are
#    identical (max 0), with k = 2 the difference is the reference itself, so its largest
#    value is the reference's peak; the double reference (on the device) checks out.
"$BIN" render --model-file "$F/scaled.cl" --models scaled:k=1,scaled:k=2 --scene spheres --size 96x64 \
    --time-sizes none --no-images --quiet --out "$T/r1" >"$T/out" 2>"$T/err" && ok || bad "render with a user model: $(cat "$T/err")"
jsoncheck usermodel_render_k_c_n_identity "$T/r1/render.json" && ok || bad "render of k c^n: identity figures"

# 8. The main job with a user model (quick grids): it joins the sweep, the heatmaps (field.cl
#    built with it) and the images. f = 2 c^n: relative error exactly 1 in every cell.
"$BIN" all --quick --model-file "$F/scaled.cl" --models fq2,scaled:k=2 --out "$T/all" >"$T/out" 2>"$T/err" \
    && ok || bad "all with a user model: $(tail -5 "$T/err")"
[ -s "$T/all/heatmap_scaled_k2.png" ] && ok || bad "all: no heatmap of the user model"
jsoncheck usermodel_frontier_all_models_with_user "$T/all/frontier.json" && ok || bad "the frontier of all --models with a user model"
jsoncheck usermodel_user_model_error_field "$T/all/field_scaled_k2.json" && ok || bad "the user model's error field"

# 9. Throughput: throughput.cl built with the user model; its rate is measured and its values
#    agree with its double reference (the model is fq2's formula at a = 0.448, b = 0.099).
"$BIN" throughput --model-file "$F/quad.cl" --models myquad --reps 1 --min-time 0.002 --variants default \
    --n-modes uniform --no-sweep --no-host-c --quiet --out "$T/tp" 2>"$T/err" && ok || bad "throughput with a user model: $(tail -3 "$T/err")"
jsoncheck usermodel_user_model_measured_by_throughput "$T/tp/throughput.json" && ok || bad "the user model measured by throughput"

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
jsoncheck usermodel_doc_example_figures "$T/doc/accuracy.json" "$DOC" && ok || bad "the doc's example gives other figures than the doc states"

# 12. native_* functions compile in every build; in the reference they are exact, so a model
#     that is the Phong lobe through native_powr has the Phong lobe's figures (0, to rounding).
"$BIN" accuracy --model 'np=native_powr(c, n)' --n-max 50 --samples 256 --out "$T/np" --quiet 2>"$T/err" \
    && ok || bad "a model with native_powr: $(cat "$T/err")"
jsoncheck usermodel_native_powr_exact_reference "$T/np/accuracy.json" && ok || bad "native_powr is exact in the reference"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
