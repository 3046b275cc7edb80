#!/usr/bin/env bash
# test_shaderlang_cli.sh - shader-language models (host/core/shader/shaderlang.c) through the accuracy
# command: the same lobe written in OpenCL C, GLSL and HLSL, and the issue's pasted GLSL
# statements (Lyon's lobe with k = 2 written in GLSL) give the same printed figures as the
# built-in lyon:k=2, and an error in line 3 of a GLSL file is reported at line 3. (Each user
# model costs a kernel build: tests/test_shaderlang.c checks more writings on the host.)
#
# Expected values are identities, not the program's output: (1 - k n (1 - c))^4 with k = 1/4
# is (1 - n (1 - c) / 2^2)^(2^2), which is lyon:k=2 (docs/definitions.md), so every row of the
# table must read as lyon:k=2's, digit for digit (the models' names and the speed column aside).
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
F=$SRC/tests/test_shaderlang_files

# 1. Five writings of one lobe in one run.
"$BIN" accuracy --model-file "$F/quartic_cl.cl" --model-file "$F/quartic_glsl.glsl" \
    --model-file "$F/quartic_hlsl.hlsl" \
    --model 'q4=t = 1 - 0.25*n*(1-c); t = max(t, 0); return t*t*t*t;' \
    --models lyon:k=2,quartic_cl:k=0.25,quartic_glsl:k=0.25,quartic_hlsl:k=0.25,q4 \
    --n-min 2 --n-max 40 --samples 64 --out "$T/a" >"$T/out" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "accuracy of the shader-language models: exit $rc: $(tail -5 "$T/err")"
# The table's rows without the label (first column) and the speed (last column).
rows=$(awk '$1 ~ /^(lyon:k=2|quartic_cl:k=0.25|quartic_glsl:k=0.25|quartic_hlsl:k=0.25|q4)$/ {
    $1 = ""; $NF = ""; print }' "$T/out")
[ "$(printf '%s\n' "$rows" | wc -l)" -eq 5 ] && ok || bad "expected 5 rows in the table: $(cat "$T/out")"
[ "$(printf '%s\n' "$rows" | sort -u | wc -l)" -eq 1 ] && ok || bad "the five writings of lyon:k=2 print different figures:
$(cat "$T/out")"
jsoncheck shaderlang_cli_five_writings_lyon_k2 "$T/a/accuracy.json" && ok || bad "the five writings have lyon:k=2's figures in accuracy.json"

# 2. An error in line 3 of a GLSL file is reported at line 3 (and its column), exit 2: the message
#    of the GLSL reference compiler (glslang), which checks a .glsl file before it is translated.
expect 2 "line3.glsl:3:27: 'undefined_thing': undeclared identifier \\(glslang, the GLSL reference compiler\\)" accuracy \
    --model-file "$F/line3.glsl" --n-max 4 --samples 16 --out "$T/e1"
[ ! -e "$T/e1" ] && ok || bad "a failed model still wrote $T/e1"

# 3. BRDF Explorer files (full BRDFs, L = N, theta_h swept, luminance): Blinn-Phong against the
#    built-in blinn and Cook-Torrance (GGX) against the built-in ct-ggx are those models, so their
#    errors are rounding (the double figures; the float sweep's check is not meant for errors of
#    1e-14 and may say so). Past theta_h = 45 degrees V is below the horizon and the BRDF is 0,
#    so against the lobe blinn the attenuation zone holds c^n there: at n = 2 and x = pi/4, 1/2.
#    ct_full.hlsl is the same Cook-Torrance as a full BRDF of (L, V, N, X, Y) in HLSL, F0 = 0.5.
"$BIN" accuracy --model-file "$F/blinnphong.brdf" --model-file "$F/ct_ggx.brdf" --model-file "$F/ct_full.hlsl" \
    --n-min 2 --n-max 60 --samples 64 --out "$T/b" >"$T/out" 2>"$T/err" && ok || bad "accuracy of .brdf files: $(tail -5 "$T/err")"
jsoncheck shaderlang_cli_brdf_blinn_phong_cook_torrance "$T/b/accuracy.json" && ok || bad ".brdf Blinn-Phong and Cook-Torrance are the built-in models"
"$BIN" throughput --model-file "$F/blinnphong.brdf" --models blinnphong,blinn --reps 1 --min-time 0.002 \
    --variants default --n-modes uniform --no-sweep --no-host-c --quiet --out "$T/tp" 2>"$T/err" \
    && ok || bad "throughput of a .brdf file: $(tail -3 "$T/err")"
jsoncheck shaderlang_cli_brdf_model_measured_by_throughput "$T/tp/throughput.json" && ok || bad "the .brdf model measured by throughput"
"$BIN" render --model-file "$F/blinnphong.brdf" --models blinnphong --scene spheres --size 64x48 --time-sizes none \
    --no-images --quiet --out "$T/r" >"$T/out" 2>"$T/err" && ok || bad "render of a .brdf file: $(tail -3 "$T/err")"
expect 2 "bad_shader.brdf:8:47: use of undeclared identifier 'nn'" accuracy --model-file "$F/bad_shader.brdf" \
    --n-max 4 --samples 16 --out "$T/e2"

# 4. Engine-style files (written for these tests): a Filament-style D_GGX chosen by #if (with
#    alpha = sqrt(2/(n + 2)) it is the built-in ggx, docs/definitions.md: the same printed figures,
#    by either branch, -D TARGET_MOBILE=1 choosing the other), and a three.js-style
#    BRDF_BlinnPhong with an overloaded F_Schlick: D G F = (n/2 + 1)/pi c^n / 4 = phongn / 4, so
#    its max delta against phongn is 75% (1 - 1/4).
for mobile in 0 1; do
    "$BIN" accuracy -D TARGET_MOBILE=$mobile --model-file "$F/filament_dggx.glsl" --model-file "$F/threejs_blinnphong.glsl" \
        --models ggx,fdggx,threeblinn --n-min 2 --n-max 60 --samples 64 --out "$T/g$mobile" >"$T/out" 2>"$T/err" \
        && ok || bad "accuracy of the engine-style files (TARGET_MOBILE=$mobile): $(tail -3 "$T/err")"
    rows=$(awk '$1 ~ /^(ggx|fdggx)$/ { $1 = ""; $NF = ""; print }' "$T/out")
    [ "$(printf '%s\n' "$rows" | wc -l)" -eq 2 ] && [ "$(printf '%s\n' "$rows" | sort -u | wc -l)" -eq 1 ] && ok ||
        bad "the Filament-style D_GGX (TARGET_MOBILE=$mobile) does not print ggx's figures: $(cat "$T/out")"
    awk '$1 == "threeblinn" && $3 == "75%" { found = 1 } END { exit !found }' "$T/out" && ok ||
        bad "the three.js-style BRDF_BlinnPhong's max delta against phongn is not 75%: $(cat "$T/out")"
done

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
