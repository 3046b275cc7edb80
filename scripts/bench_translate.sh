#!/usr/bin/env bash
# bench_translate.sh - how long the shader-language translator (host/core/shader/shaderlang*.c) takes
# for a 300-line shader: helper functions, vectors, if/else, a constant loop, and two nested
# constant loops of 32 (1024 bodies, the case that was cubic), each as a .glsl file (checked by
# glslang first, then translated) and under a name brdfbench's parser reads alone. A benchmark,
# not a test: it asserts nothing, and prints the median wall time of REPEATS translations of
# each text.
# Only the translation is timed (scripts/bench_translate.c, linked against build/libbrdfcore.a):
# no OpenCL build, no host compiler.
#
#   scripts/bench_translate.sh [BUILD_DIR] [REPEATS]     (defaults: build, 21)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
repeats=${2:-21}
[ -f "$build/libbrdfcore.a" ] || { echo "bench_translate: $build/libbrdfcore.a is missing (build first)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
${CC:-cc} -O2 -Ihost/core -Ihost/output scripts/bench_translate.c "$build/libbrdfcore.a" \
    -lOpenCL -ltcc -lglslang -lMachineIndependent -lOSDependent -lHLSL -lOGLCompiler -lGenericCodeGen \
    -lglslang-default-resource-limits -lglslang -lMachineIndependent -lm -lpthread -ldl -lstdc++ \
    -o "$tmp/bench_translate"

# The 300-line shader: 27 helpers of 10 lines each, then the model function.
{
  echo "/* brdfbench-model"
  echo " * name: long300"
  echo " */"
  for ((k = 0; k < 27; ++k)); do
    cat <<GLSL
float helper$k(float x, float n) {
    vec3 v = vec3(x, 1.0 - x, 0.5 * x);
    float d = dot(v, v) + float($k) * 0.001;
    if (d > 1.0) {
        d = sqrt(d);
    } else {
        d = d * d;
    }
    return pow(max(d, 0.0), 1.0 + 0.01 * n);
}
GLSL
  done
  echo "float long300(float c, float n) {"
  echo "    float s = 0.0;"
  for ((k = 0; k < 27; ++k)); do
    echo "    s += helper$k(c, n) * 0.037;"
  done
  echo "    for (int i = 0; i < 8; i++) {"
  echo "        s = s * 0.5 + c * float(i) * 0.01;"
  echo "    }"
  echo "    return s;"
  echo "}"
} >"$tmp/long300.glsl"
# the same text through the preprocessor (glslang): an #if around it and a function-like macro
{ echo "#define SCALE(x) ((x) * 0.037)"; echo "#if 1"; sed 's/\* 0\.037;/;/' "$tmp/long300.glsl" | sed '/^\/\*/,/\*\//d'; echo "#endif"; } >"$tmp/long300pp.glsl"
sed -i 's/    s += \(helper[0-9]*(c, n)\);/    s += SCALE(\1);/' "$tmp/long300pp.glsl"
sed -i 's/long300(/long300pp(/' "$tmp/long300pp.glsl"
# two nested constant loops of 32: 1024 bodies
cat >"$tmp/nested32.glsl" <<'GLSL'
float nested32(float c, float n) {
    float s = 0.0;
    for (int i = 0; i < 32; i++) {
        for (int j = 0; j < 32; j++) {
            float t = c * float(i + j) * 0.001;
            s += t;
        }
    }
    return s;
}
GLSL

median() { sort -g | awk '{ v[NR] = $1 } END { if (NR % 2) print v[(NR + 1) / 2]; else printf "%.6f\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
printf '%-16s %6s %12s %14s\n' shader lines "median s" "output bytes"
# a .glsl file is also parsed by glslang (the reference compiler's check); the same text named
# .shader is read by brdfbench's own parser alone
cp "$tmp/long300.glsl" "$tmp/long300.shader"
cp "$tmp/nested32.glsl" "$tmp/nested32.shader"
for f in long300.glsl long300pp.glsl long300.shader nested32.glsl nested32.shader; do
  "$tmp/bench_translate" "$tmp/$f" "$repeats" >"$tmp/$f.t"
  printf '%-16s %6d %12s %14s\n' "$f" "$(wc -l <"$tmp/$f")" "$(cut -d' ' -f1 "$tmp/$f.t" | median)" \
    "$(head -1 "$tmp/$f.t" | cut -d' ' -f2)"
done
