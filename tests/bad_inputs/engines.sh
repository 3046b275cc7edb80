# engines.sh - bad-input rows of engine code as pasted (host/core/shader/shaderlang_parse.c,
# shaderlang_emit.c): array parameters (GLSL's `const in vec3 v[4]`) are passed in, by value, with a
# constant length; what does not fit is refused at its column with exit 2 (*.shader files: brdfbench's
# own check; a .glsl file's mismatch is glslang's, the reference compiler). Sourced by
# tests/test_cli_errors.sh (its `t` helper; the working folder is its $T).
mkdir -p engines_in
w() { printf '%s\n' "$2" >"engines_in/$1"; }
w nolen.shader 'float g(float w[]) { return w[0]; } float f(float c, float n) { return c; }'
w outarr.shader 'float g(out float w[2]) { return 1.0; } float f(float c, float n) { float a[2] = float[2](c, n); return g(a); }'
w wronglen.shader 'float g(float w[3]) { return w[0]; } float f(float c, float n) { float a[2] = float[2](c, n); return g(a); }'
w notarr.shader 'float g(float w[2]) { return w[0]; } float f(float c, float n) { return g(c); }'
w arrtoscalar.shader 'float g(float w) { return w; } float f(float c, float n) { float a[2] = float[2](c, n); return g(a); }'
w wronglen.glsl 'float g(float w[3]) { return w[0]; } float f(float c, float n) { float a[2] = float[2](c, n); return g(a); }'
t 2 "^brdfbench accuracy: engines_in/nolen.shader:1:17: an array parameter needs its length \(w\[N\]\)$" accuracy --model-file engines_in/nolen.shader
t 2 "^brdfbench accuracy: engines_in/outarr.shader:1:19: an out array parameter: array parameters are passed in only$" accuracy --model-file engines_in/outarr.shader
t 2 "^brdfbench accuracy: engines_in/wronglen.shader:1:104: argument 1 of g takes a float\[3\]: pass an array of that type and length$" accuracy --model-file engines_in/wronglen.shader
t 2 "^brdfbench accuracy: engines_in/notarr.shader:1:75: argument 1 of g takes a float\[2\]: pass an array of that type and length$" accuracy --model-file engines_in/notarr.shader
t 2 "^brdfbench accuracy: engines_in/arrtoscalar.shader:1:98: argument 1 of g is an array: it takes a float$" accuracy --model-file engines_in/arrtoscalar.shader
t 2 "^brdfbench accuracy: engines_in/wronglen.glsl:1:7: 'g': no matching overloaded function found \(glslang, the GLSL reference compiler\)$" accuracy --model-file engines_in/wronglen.glsl
