#!/usr/bin/env bash
# test_accuracy_pictures.sh - pictures of any model without `all`: accuracy --pictures writes
# each model's heatmap and the max delta / max Delta against n plots, user models included;
# plot and heatmap redraw a run with a user model in a process that does not know it; and a
# user model that --models does not name is measured (with a note), not dropped.
#
# Expected values are closed forms: f = k c^n against c^n has delta = |k - 1| at every point and
# Delta = |k - 1| c^n, largest over the attenuation zone at its start x_e (c^n = e^-0.511).
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init

# 1. --models fq2 with --model z: z is measured as well, and a note says so.
"$BIN" accuracy --models fq2 --model 'z=0.5*pow(c, n)' --n-min 2 --n-max 8 --samples 64 --json - \
    >"$T/a.json" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "accuracy --models fq2 --model z: exit $rc: $(tail -3 "$T/err")"
grep -q "user model 'z' (--model z) is not in --models: measured as well" "$T/err" && ok || bad "no note about z: $(cat "$T/err")"
jsoncheck accuracy_pictures_z_beside_fq2 "$T/a.json" && ok || bad "z is measured beside fq2"

# 2. --pictures: heatmaps of both models and the two plots, the user model in them.
"$BIN" accuracy --models fq2,z --model 'z=0.5*pow(c, n)' --n-min 2 --n-max 50 --samples 64 --pictures \
    --out "$T/run" >"$T/out" 2>"$T/err" && ok || bad "accuracy --pictures: $(tail -3 "$T/err")"
for f in field_fq2.json field_z.json heatmap_fq2.png heatmap_z.png plots.json max_rel_error_epicentre_vs_n.png \
         max_abs_error_vs_n.png; do
    [ -s "$T/run/$f" ] && ok || bad "accuracy --pictures wrote no $f"
done
jsoncheck accuracy_pictures_field_z_closed_form "$T/run/field_z.json" && ok || bad "the field of z = 0.5 c^n has its closed-form peaks"
jsoncheck accuracy_pictures_both_models_both_plots "$T/run/plots.json" && ok || bad "both models in both plots"

# 3. plot and heatmap redraw it without the user model being defined.
rm -f "$T/run/heatmap_z.png"
"$BIN" plot "$T/run" >"$T/out" 2>"$T/err" && ok || bad "plot of a run with a user model: $(cat "$T/err")"
[ -s "$T/run/heatmap_z.png" ] && ok || bad "plot did not redraw heatmap_z.png"
"$BIN" heatmap "$T/run" --label z >"$T/out" 2>"$T/err" && ok || bad "heatmap --label z: $(cat "$T/err")"
# A field file written before it carried the formula and lobe still redraws.
python3 - "$T/run/field_z.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
del d["formula"], d["lobe"]
json.dump(d, open(sys.argv[1], "w"))
PY
"$BIN" heatmap "$T/run" --label z >"$T/out" 2>"$T/err" && ok || bad "heatmap of an older field file: $(cat "$T/err")"

# 4. --pictures needs a run folder.
expect 2 "--pictures writes into the run folder" accuracy --models fq2 --pictures --json "$T/x.json" --n-max 4

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
