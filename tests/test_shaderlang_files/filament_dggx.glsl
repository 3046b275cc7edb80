/* brdfbench-model
 * name: fdggx
 * function: lobe
 * reference: phongn
 * define: SPECULAR_AMBIENT_OCCLUSION=0
 */
// A Filament-style GGX distribution, chosen by #if as an engine file chooses it (written for
// brdfbench's tests). With alpha = sqrt(2 / (n + 2)) it is the built-in ggx.
#define PI_F 3.14159265359
#define MEDIUMP_MAX 65504.0
#define clampMediump(x) min(x, MEDIUMP_MAX)
#ifndef TARGET_MOBILE
#define TARGET_MOBILE 0
#endif

#if TARGET_MOBILE
float distribution(float linearRoughness, float NoH) {
    // the form written for half precision: sin^2 theta_h kept apart from the cosine term
    float sin2 = 1.0 - NoH * NoH;
    float ac = NoH * linearRoughness;
    float ratio = linearRoughness / (sin2 + ac * ac);
    return clampMediump(ratio * ratio * (1.0 / PI_F));
}
#elif defined(SPECULAR_AMBIENT_OCCLUSION)
float distribution(float roughness, float NoH) {
    float a2 = roughness * roughness;
    float f = (NoH * a2 - NoH) * NoH + 1.0;
    return a2 / (PI_F * f * f);
}
#else
#error no distribution chosen
#endif

float lobe(float c, float n) {
    return distribution(sqrt(2.0 / (n + 2.0)), c);
}
