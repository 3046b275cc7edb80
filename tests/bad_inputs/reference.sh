# reference.sh - bad inputs of accuracy --reference naming a user model (its file, user:NAME) or a
# measured material (merl:FILE.binary): each refused with exit 2 and one line naming the flag and
# what it accepts, before any device work.
cat >"$T/rfull.glsl" <<'EOF2'
/* brdfbench-model
 * name: rfull
 * reference: ct-ggx
 * lobe: theta_h
 */
float rfull(vec3 L, vec3 V, vec3 N, float n)
{
    return pow(max(dot(N, normalize(L + V)), 0.0), n);
}
EOF2
cat >"$T/rlobe.cl" <<'EOF2'
/* brdfbench-model
 * name: rlobe
 */
REAL rlobe(REAL c, REAL n) { return pow(c, n); }
EOF2
printf 'not a table' >"$T/rshort.binary"
t 2 "^brdfbench accuracy: --reference: cannot read $T/none.glsl: " \
    accuracy --model-file "$T/rfull.glsl" --reference "$T/none.glsl"
t 2 "^brdfbench accuracy: --reference: $T/none.binary: " \
    accuracy --model-file "$T/rfull.glsl" --reference "merl:$T/none.binary"
t 2 "^brdfbench accuracy: --reference: $T/rshort.binary: " \
    accuracy --model-file "$T/rfull.glsl" --reference "merl:$T/rshort.binary"
t 2 "^brdfbench accuracy: --reference: merl: names no file \(accepted: merl:FILE.binary" \
    accuracy --model-file "$T/rfull.glsl" --reference merl:
t 2 "^brdfbench accuracy: --reference: user:nosuch: no user model of that name \(accepted: rfull\)" \
    accuracy --model-file "$T/rfull.glsl" --reference user:nosuch
t 2 "^brdfbench accuracy: --reference: user:blinn: no user model of that name" \
    accuracy --model-file "$T/rfull.glsl" --reference user:blinn
t 2 "^brdfbench accuracy: --reference: rlobe is a lobe of c and n, not a BRDF of \(L, V\), so it cannot be the reference of the full BRDF rfull" \
    accuracy --model-file "$T/rfull.glsl" --reference "$T/rlobe.cl"
t 2 "^brdfbench accuracy: --reference: rfull is the reference of full BRDFs only, and blinn is a lobe model of c and n \(accepted for a lobe model: a built-in" \
    accuracy --models blinn --reference "$T/rfull.glsl"
t 2 "^brdfbench accuracy: --reference: rfull is evaluated by the host at each of 1.342e\+08 grid points x axis values \(accepted: at most 16777216" \
    accuracy --model-file "$T/rfull.glsl" --reference "$T/rfull.glsl" --hemisphere-grid 512x512x512 --axis-points 1
# a gates file's "reference" (docs/gates.md): hemisphere.* gates only, a known model, no lobe
printf '{"gates": [{"model": "fq2", "metric": "epicentre.max_rel", "reference": "ggx", "max": 1}]}' >"$T/rgate1.json"
printf '{"gates": [{"model": "ct-ggx", "metric": "hemisphere.rms", "reference": "nosuch", "max": 1}]}' >"$T/rgate2.json"
printf '{"gates": [{"model": "sq", "expression": "c", "metric": "epicentre.max_rel", "max": 1}, {"model": "ct-ggx", "metric": "hemisphere.rms", "reference": "sq", "max": 1}]}' >"$T/rgate3.json"
t 2 "^brdfbench gate: $T/rgate1.json:1:73: gate 1: \"reference\" is read only by the hemisphere.\* metrics \(this gate's is epicentre.max_rel\)" \
    gate "$T/rgate1.json"
t 2 "^brdfbench gate: $T/rgate2.json:1:73: gate 1: \"reference\": unknown model 'nosuch' \(accepted: phong, blinn," \
    gate "$T/rgate2.json"
t 2 "^brdfbench gate: $T/rgate3.json:1:150: gate 2: \"reference\": sq is a lobe of c and n, not a BRDF of \(L, V\)" \
    gate "$T/rgate3.json"
# a user lobe model as the reference of a lobe model: its text must compile as C (the host evaluates
# it in double at every sample), and its table of n values x 2 zones x samples must fit
cat >"$T/rnotc.cl" <<'EOF2'
/* brdfbench-model
 * name: rnotc
 */
REAL rnotc(REAL c, REAL n) { return mad24(1, 1, 0) * pow(c, n); }
EOF2
t 2 "^brdfbench accuracy: --reference: rnotc: its text does not compile as C for the host's double evaluation \(.*\), so it cannot be a reference \(accepted: a model file whose text is C, a built-in\)" \
    accuracy --models cq2 --reference "$T/rnotc.cl"
t 2 "^brdfbench accuracy: --samples: rlobe is evaluated by the host at each of 1.309e\+08 samples \(999 values of n x 2 zones x 65536 samples\) \(accepted: at most 16777216 with a user model as --reference\)" \
    accuracy --models cq2 --reference "$T/rlobe.cl" --samples 65536
