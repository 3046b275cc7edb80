# exact.sh - bad inputs of a .brdf file's bools as parameters (--param NAME=0|1 in accuracy,
# throughput and render) and of --axis PARAM:ROLE: each refused with exit 2 and one line naming
# the flag and what it accepts, before any device work.
cat >"$T/xbool.brdf" <<'EOF2'
analytic
::begin parameters
float n 1 1000 50
bool divide_by_NdotL 1
::end parameters
::begin shader
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
{
    float f = pow(max(dot(N, normalize(L + V)), 0.0), n);
    if (divide_by_NdotL)
        f = f / dot(N, L);
    return vec3(f);
}
::end shader
EOF2
t 2 "^brdfbench accuracy: --param: divide_by_NdotL=2 is out of range \(accepted: 0 or 1\)" \
    accuracy --model-file "$T/xbool.brdf" --reference blinn --param divide_by_NdotL=2
t 2 "^brdfbench accuracy: --param: divide_by_NdotL=0.5 is out of range \(accepted: 0 or 1\)" \
    accuracy --model-file "$T/xbool.brdf" --reference blinn --param divide_by_NdotL=0.5
t 2 "^brdfbench throughput: --param divide_by_NdotL=3: model 'xbool': parameter divide_by_NdotL='3' must be an integer in \[0, 1\]" \
    throughput --model-file "$T/xbool.brdf" --param divide_by_NdotL=3
t 2 "^brdfbench render: --param: no listed model has a parameter 'nosuch'" \
    render --model-file "$T/xbool.brdf" --param nosuch=1
t 2 "^brdfbench throughput: --param: 'divide_by_NdotL' is not NAME=VALUE" \
    throughput --model-file "$T/xbool.brdf" --param divide_by_NdotL
t 2 "^brdfbench accuracy: --axis: 'n:nosuch': the role 'nosuch' is unknown \(accepted roles: n, alpha, roughness, m" \
    accuracy --model-file "$T/xbool.brdf" --reference blinn --axis n:nosuch
t 2 "^brdfbench accuracy: --axis: xbool:divide_by_NdotL=1 has no parameter 'c' \(accepted: divide_by_NdotL\)" \
    accuracy --model-file "$T/xbool.brdf" --reference blinn --axis c:alpha
t 2 "^brdfbench accuracy: --axis: ct-ggx:F0=0.5 has no parameter 'c' \(accepted: F0\)" \
    accuracy --models ct-ggx --axis c:alpha
t 2 "^brdfbench accuracy: --axis: F0:alpha=0.5:2 is out of range \(accepted: 0.00141421 <= F0 <= 1, the range of both F0 and alpha" \
    accuracy --models ct-ggx --axis F0:alpha=0.5:2
