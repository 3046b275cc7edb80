/* brdfbench-model
 * name: stylelo
 * reference: ct-ggx
 * lobe: theta_h
 */
// Written for brdfbench's tests in the style of a tutorial PBR fragment shader: functions of
// vectors (N, H, V, L) and a roughness, a Schlick-GGX geometry term with k = (r + 1)^2 / 8 used
// twice by a Smith product, Fresnel from F0 = mix(0.04, albedo, metallic), a const PI, and
// the Cook-Torrance quotient with a small epsilon in the denominator.
const float PI = 3.14159265359;

float DistributionGGX(vec3 N, vec3 H, float roughness)
{
    float a = roughness * roughness;
    float a2 = a * a;
    float NdotH = max(dot(N, H), 0.0);
    float NdotH2 = NdotH * NdotH;
    float nom = a2;
    float denom = (NdotH2 * (a2 - 1.0) + 1.0);
    denom = PI * denom * denom;
    return nom / denom;
}

float GeometrySchlickGGX(float NdotV, float roughness)
{
    float r = (roughness + 1.0);
    float k = (r * r) / 8.0;
    return NdotV / (NdotV * (1.0 - k) + k);
}

float GeometrySmith(vec3 N, vec3 V, vec3 L, float roughness)
{
    float NdotV = max(dot(N, V), 0.0);
    float NdotL = max(dot(N, L), 0.0);
    return GeometrySchlickGGX(NdotV, roughness) * GeometrySchlickGGX(NdotL, roughness);
}

vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    return F0 + (1.0 - F0) * pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
}

vec3 specularCookTorrance(vec3 N, vec3 V, vec3 L, float roughness, vec3 albedo, float metallic)
{
    vec3 H = normalize(V + L);
    vec3 F0 = vec3(0.04);
    F0 = mix(F0, albedo, metallic);
    float NDF = DistributionGGX(N, H, roughness);
    float G = GeometrySmith(N, V, L, roughness);
    vec3 F = fresnelSchlick(max(dot(H, V), 0.0), F0);
    vec3 numerator = NDF * G * F;
    float denominator = 4.0 * max(dot(N, V), 0.0) * max(dot(N, L), 0.0) + 0.0001;
    return numerator / denominator;
}

vec3 stylelo(vec3 L, vec3 V, vec3 N, float n) { return specularCookTorrance(N, V, L, sqrt(sqrt(2.0 / (n + 2.0))), vec3(0.9, 0.6, 0.3), 0.5); }
