/* brdfbench-model
 * name: stylebj
 * reference: ct-ggx
 * lobe: theta_h
 */
// Written for brdfbench's tests in the style of an engine's PBR function file: function-like
// macros, #ifdef switches, a square() helper, Trowbridge-Reitz, a correlated Smith visibility
// with sqrt, and Schlick's Fresnel between reflectance0 and reflectance90 with pow.
#define PBR_CORRELATED_VISIBILITY
#define saturate(x) clamp(x, 0.0, 1.0)
#define absEps(x) (abs(x) + 1e-6)
const float PI = 3.1415926535897932384626433832795;

float square(float value) { return value * value; }

float normalDistributionFunction_TrowbridgeReitz(float NdotH, float alphaG)
{
    float a2 = square(alphaG);
    float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}

#ifdef PBR_CORRELATED_VISIBILITY
float smithVisibility_GGXCorrelated(float NdotL, float NdotV, float alphaG)
{
    float a2 = alphaG * alphaG;
    float GGXV = NdotL * sqrt(NdotV * (NdotV - a2 * NdotV) + a2);
    float GGXL = NdotV * sqrt(NdotL * (NdotL - a2 * NdotL) + a2);
    return 0.5 / (GGXV + GGXL);
}
#else
float smithVisibility_GGXCorrelated(float NdotL, float NdotV, float alphaG) { return 0.25; }
#endif

vec3 fresnelSchlickGGX(float VdotH, vec3 reflectance0, vec3 reflectance90)
{
    return reflectance0 + (reflectance90 - reflectance0) * pow(1.0 - VdotH, 5.0);
}

vec3 computeSpecularLighting(vec3 N, vec3 L, vec3 V, float alphaG, vec3 r0)
{
    vec3 H = normalize(V + L);
    float NdotL = saturate(dot(N, L));
    float NdotV = absEps(dot(N, V));
    float NdotH = saturate(dot(N, H));
    float VdotH = saturate(dot(V, H));
    vec3 F = fresnelSchlickGGX(VdotH, r0, vec3(1.0));
    float D = normalDistributionFunction_TrowbridgeReitz(NdotH, alphaG);
    float Vis = smithVisibility_GGXCorrelated(NdotL, NdotV, alphaG);
    return F * (D * Vis);
}

vec3 stylebj(vec3 L, vec3 V, vec3 N, float n) { return computeSpecularLighting(N, L, V, sqrt(2.0 / (n + 2.0)), vec3(0.5, 0.4, 0.3)); }
