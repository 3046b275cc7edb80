/* brdfbench-model
 * name: ct_full
 * description: Cook-Torrance with GGX as a full BRDF in HLSL, F0 a parameter
 * reference: ct-ggx
 * lobe: theta_h
 * param: F0 0 1 0.5
 */
static const float PI = 3.14159265358979323846f;

float G1(float x, float a2) { return 2.0f * x / (x + sqrt(a2 + (1.0f - a2) * x * x)); }

float3 ct_full(float3 L, float3 V, float3 N, float3 X, float3 Y, float n, float F0)
{
    float3 H = normalize(L + V);
    float NdotH = dot(N, H), VdotH = dot(V, H);
    float NdotL = max(dot(N, L), 1e-6f), NdotV = max(dot(N, V), 1e-6f);
    float alpha = sqrt(2.0f / (n + 2.0f));
    float a2 = alpha * alpha;
    float d = (1.0f - NdotH) * (1.0f + NdotH) + NdotH * NdotH * a2;
    float m = 1.0f - VdotH;
    float F = lerp(F0, 1.0f, m * m * m * m * m);
    return (a2 / (PI * d * d)) * F * G1(NdotL, a2) * G1(NdotV, a2) / (4.0f * NdotL * NdotV);
}
