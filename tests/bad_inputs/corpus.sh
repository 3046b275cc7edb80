# corpus.sh - bad .brdf headers and names (BRDF Explorer files, docs/user-models.md): rows for
# tests/test_cli_errors.sh (sourced there; `t` and the working folder are its).
brdf_body='vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(pow(max(dot(N, normalize(L + V)), 0.0), n)); }'
brdf_file() {   # brdf_file FILE HEADER-LINES...: a .brdf file with parameter n and that header
    local f=$1
    shift
    {
        printf '::begin parameters\nfloat n 1 100 10\n::end parameters\n::begin shader\n/* brdfbench-model\n'
        printf ' * %s\n' "$@"
        printf ' */\n%s\n::end shader\n' "$brdf_body"
    } >"$f"
}
brdf_file foo_key.brdf 'foo: bar'
brdf_file bad_lobe.brdf 'lobe: sideways'
brdf_file twice_lobe.brdf 'lobe: psi' 'lobe: theta_d'
brdf_file param_key.brdf 'param: k 0 1 0.5'
brdf_file no_colon.brdf 'just words'
brdf_file bad_ref.brdf 'reference: nosuch'
mkdir -p brdf_a brdf_b
brdf_file brdf_a/phong.brdf 'lobe: theta_h'
cp brdf_a/phong.brdf brdf_b/phong.brdf
t 2 "^brdfbench throughput: foo_key.brdf:6: unknown header key 'foo' \(accepted in a .brdf file: name, reference, lobe, description;" \
    throughput --model-file foo_key.brdf
t 2 "^brdfbench throughput: bad_lobe.brdf:6: lobe 'sideways' is unknown \(accepted in a .brdf file: theta_h, psi, theta_d\)" \
    throughput --model-file bad_lobe.brdf
t 2 "^brdfbench accuracy: twice_lobe.brdf:7: 'lobe' is declared twice" accuracy --model-file twice_lobe.brdf
t 2 "^brdfbench render: param_key.brdf:6: unknown header key 'param' \(accepted in a .brdf file: name, reference, lobe, description; its parameters are those of ::begin parameters\)" \
    render --model-file param_key.brdf
t 2 "^brdfbench throughput: no_colon.brdf:6: expected 'key: value' in the brdfbench-model header \(keys of a .brdf file: name, reference, lobe, description\)" \
    throughput --model-file no_colon.brdf
t 2 "^brdfbench throughput: bad_ref.brdf:6: reference 'nosuch' is not a built-in model \(see brdfbench list\)" \
    throughput --model-file bad_ref.brdf
# two files called phong.brdf: the first is phong@phong.brdf (phong is the built-in's), the second is refused
t 2 "^brdfbench throughput: brdf_b/phong.brdf: user model 'phong@phong.brdf' is already defined by brdf_a/phong.brdf" \
    throughput --model-file brdf_a/phong.brdf --model-file brdf_b/phong.brdf
