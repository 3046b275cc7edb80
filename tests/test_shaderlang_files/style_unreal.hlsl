/* brdfbench-model
 * name: styleue
 * reference: ct-ggx
 * lobe: theta_h
 * param: Spec 0 1 0.5
 */
// Written for brdfbench's tests in the style of an engine's HLSL BRDF library: a PI macro, a
// Pow5 helper, rcp and saturate, a float3 specular colour read by swizzle, GGX in a^2 form, a
// joint Smith visibility approximation and Schlick's Fresnel with a green-channel cut-off.
#define PI 3.14159265359
#define EPS_NOL 1e-5

float Pow5(float x)
{
    float x2 = x * x;
    return x2 * x2 * x;
}

float NDF_GGX(float a2, float NoH)
{
    float d = (NoH * a2 - NoH) * NoH + 1.0;
    return a2 / (PI * d * d);
}

float Vis_JointApprox(float a2, float NoV, float NoL)
{
    float a = sqrt(a2);
    float sv = NoL * (NoV * (1.0 - a) + a);
    float sl = NoV * (NoL * (1.0 - a) + a);
    return 0.5 * rcp(sv + sl);
}

float3 Fresnel_Schlick(float3 SpecularColor, float VoH)
{
    float Fc = Pow5(1.0 - VoH);
    return saturate(50.0 * SpecularColor.g) * Fc + (1.0 - Fc) * SpecularColor;
}

float3 SpecularGGX(float Roughness, float3 SpecularColor, float3 L, float3 V, float3 N)
{
    float a2 = Roughness * Roughness;
    float3 H = normalize(L + V);
    float NoH = saturate(dot(N, H));
    float NoV = max(dot(N, V), EPS_NOL);
    float NoL = max(dot(N, L), EPS_NOL);
    float VoH = saturate(dot(V, H));
    return (NDF_GGX(a2, NoH) * Vis_JointApprox(a2, NoV, NoL)) * Fresnel_Schlick(SpecularColor, VoH);
}

float3 styleue(float3 L, float3 V, float3 N, float n, float Spec) { return SpecularGGX(sqrt(2.0 / (n + 2.0)), float3(Spec, Spec * 0.9, Spec * 0.8), L, V, N); }
