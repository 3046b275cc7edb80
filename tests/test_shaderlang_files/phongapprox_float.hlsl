/* brdfbench-model
 * name: sgphongf
 * reference: phongn
 * description: phongapprox_half.hlsl's spherical-Gaussian Phong lobe written in float
 */
float SphericalGaussianLobe(float NoH, float Power)
{
    float k = Power * 1.442695;
    return exp2(k * NoH - k);
}

float sgphongf(float c, float n)
{
    float norm = (n + 2.0) * 0.1591549;
    return norm * SphericalGaussianLobe(c, n);
}
