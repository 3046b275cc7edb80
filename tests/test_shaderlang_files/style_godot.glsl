/* brdfbench-model
 * name: stylegd
 * reference: ct-ggx
 * lobe: theta_h
 */
// Written for brdfbench's tests in the style of an engine's GLSL light functions: GGX written
// with 1 - NoH^2, a height-correlated visibility through mix, Schlick's factor as a helper, and
// the specular term assembled in a function with an inout accumulator.
#define M_PI 3.14159265359

float D_GGX(float cos_theta_m, float alpha)
{
    float a = cos_theta_m * alpha;
    float k = alpha / (1.0 - cos_theta_m * cos_theta_m + a * a);
    return k * k * (1.0 / M_PI);
}

float V_GGX(float NdotL, float NdotV, float alpha)
{
    return 0.5 / mix(2.0 * NdotL * NdotV, NdotL + NdotV, alpha);
}

float SchlickFresnel(float u)
{
    float m = 1.0 - u;
    float m2 = m * m;
    return m2 * m2 * m;
}

void light_specular(vec3 N, vec3 L, vec3 V, float roughness, vec3 f0, inout vec3 specular_light)
{
    vec3 H = normalize(V + L);
    float cNdotL = max(dot(N, L), 0.0);
    float cNdotV = max(dot(N, V), 1e-4);
    float cNdotH = clamp(dot(N, H), 0.0, 1.0);
    float cLdotH = clamp(dot(L, H), 0.0, 1.0);
    float alpha_ggx = roughness * roughness;
    float D = D_GGX(cNdotH, alpha_ggx);
    float G = V_GGX(cNdotL, cNdotV, alpha_ggx);
    float f90 = clamp(dot(f0, vec3(50.0 * 0.33)), 0.0, 1.0);
    vec3 F = f0 + (f90 - f0) * SchlickFresnel(cLdotH);
    specular_light += D * G * F;
}

vec3 stylegd(vec3 L, vec3 V, vec3 N, float n) { vec3 s = vec3(0.0); light_specular(N, L, V, sqrt(sqrt(2.0 / (n + 2.0))), vec3(0.04, 0.05, 0.06), s); return s; }
