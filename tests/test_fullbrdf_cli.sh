#!/usr/bin/env bash
# test_fullbrdf_cli.sh - full BRDFs of (N, L, V) beside the built-ins: a BRDF Explorer
# Blinn-Phong file written here renders the image the built-in blinn renders, at every pixel's
# own L, V and N; throughput's physically based table times that file and a measured material
# (a MERL file written by tests/merl_synth) as rows, each with a finite rate and a passing
# device-versus-double check; render --measured shades the teapot with that material beside
# the lobes fitted to it; --measured refuses what it cannot read.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
SYN=${MERL_SYNTH:?MERL_SYNTH must name the merl_synth writer}
# the kernel cache the other tests share (POCL_CACHE_DIR of tests/CMakeLists.txt), whose builds of
# the built-in kernels this test reuses; one of its own under T when run without it
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$T/pocl-cache}"
mkdir -p "$POCL_CACHE_DIR"

# Blinn-Phong as BRDF Explorer writes it; its colour is grey, and the luminance weights
# 0.2126 + 0.7152 + 0.0722 sum to 1, so its value is (N.H)^n: the built-in blinn's
# (docs/definitions.md), which the file names as its reference.
cat >"$T/bp.brdf" <<'EOF'
analytic
::begin parameters
float n 1 1000 100
::end parameters
::begin shader
/* brdfbench-model
 * reference: blinn
 */
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    vec3 H = normalize(L + V);
    return vec3(pow(max(0.0, dot(N, H)), n));
}
::end shader
EOF

"$BIN" render --scene teapot --models blinn --model-file "$T/bp.brdf" --size 64x48 --time-sizes none \
    --tess 4 --quiet --out "$T/r" >"$T/out" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "render with bp.brdf: exit $rc: $(head -c 400 "$T/err")"
# the same 8-bit pixels give the same PNG bytes (one encoder, one size)
cmp -s "$T/r/render/teapot/blinn.png" "$T/r/render/teapot/bp.png" && ok ||
    bad "bp.brdf's teapot differs from blinn's"
jsoncheck fullbrdf_cli_bp_brdf_shaded_from_vectors "$T/r/render.json" && ok || bad "render.json: bp.brdf shaded from the vectors, equal to blinn in float"

# a Blinn-Phong material with a Lambertian term, in MERL layout
"$SYN" "$T/b64.binary" blinn 64 2.5 0.08 >/dev/null || { echo "cannot write the material"; exit 3; }
"$BIN" throughput --model-file "$T/bp.brdf" --measured "$T/b64.binary" --reps 1 --min-time 0.001 \
    --no-host-c --no-sweep --variants default --n-modes uniform --out "$T/tp" >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 0 ] && ok || bad "throughput with bp.brdf and --measured: exit $rc: $(head -c 400 "$T/err")"
grep -q "memory bandwidth, not arithmetic" "$T/out" && ok || bad "the table does not say what a lookup costs"
# a row without an albedo (a lobe, a user BRDF, a measured material) shows "-", never nan
! grep -qw "nan" "$T/out" && ok || bad "the physically based table prints nan: $(grep -w nan "$T/out" | head -2)"
# the sweep timing of a run whose only model is a user BRDF says why nothing was timed
"$BIN" throughput --model-file "$T/bp.brdf" --reps 1 --min-time 0.001 --no-host-c --variants default \
    --n-modes uniform --out "$T/tp2" >"$T/out" 2>"$T/err"
grep -q "accuracy sweep: not measured (no model has a tuned C loop to compare with (user models have none))" "$T/out" &&
    ok || bad "the sweep timing's reason: $(grep 'accuracy sweep' "$T/out")"
jsoncheck fullbrdf_cli_physical_user_measured_rows "$T/tp/physical.json" && ok || bad "physical.json: the user and measured rows"

# the teapot shaded with the material beside its fitted lobes: the Blinn-Phong fit is the
# written material (n 64, ks 2.5, kd 0.08, within 0.1%), so its image is the analytic
# E (N.L) (ks (N.H)^n + kd) shading, and the device's nearest-cell lookup must stay within the
# table's cell size of it: rms below 1% and max below 10% of the peak radiance
"$BIN" render --scene teapot --models blinn --measured "$T/b64.binary" --size 96x72 --time-sizes none --tess 4 \
    --quiet --out "$T/rm" >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 0 ] && ok || bad "render --measured: exit $rc: $(head -c 400 "$T/err")"
for f in measured_b64.png measured_b64_blinn-phong_fit_error.png measured_b64_blinn-phong_fit_signed_error.png \
    measured_b64_ct-ggx_fit.png; do
    [ -s "$T/rm/render/teapot/$f" ] && ok || bad "render --measured wrote no $f"
done
jsoncheck fullbrdf_cli_render_measured_material_beside_fits "$T/rm/render.json" && ok || bad "render.json: the measured material beside its fits"

# bad input: exit 2 naming the flag, nothing written
expect 2 "^brdfbench render: --measured: $T/none.binary: " render --measured "$T/none.binary" --out "$T/bad4"
expect 2 "^brdfbench throughput: --measured: $T/none.binary: " throughput --measured "$T/none.binary" --out "$T/bad1"
"$SYN" "$T/short.binary" pattern short >/dev/null
expect 2 "^brdfbench throughput: --measured: $T/short.binary: " throughput --measured "$T/short.binary" --out "$T/bad2"
mkdir -p "$T/five"
for k in 1 2 3 4 5; do cp "$T/b64.binary" "$T/five/m$k.binary"; done
expect 2 "--measured: $T/five: 5 materials, at most 4 accepted" throughput --measured "$T/five" --out "$T/bad3"
[ -e "$T/bad1" ] || [ -e "$T/bad2" ] || [ -e "$T/bad3" ] || [ -e "$T/bad4" ] && bad "a refused --measured wrote a run folder" || ok

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
