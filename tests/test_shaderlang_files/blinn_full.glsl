// A full BRDF of (L, V, N) without a header: Blinn-Phong, measured with L = N and theta_h swept
// (lobe theta_h, reference blinn by default).
float blinn_full(vec3 L, vec3 V, vec3 N, float n)
{
    vec3 H = normalize(L + V);
    return pow(max(dot(N, H), 0.0), n);
}
