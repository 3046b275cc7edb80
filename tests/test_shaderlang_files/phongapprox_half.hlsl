/* brdfbench-model
 * name: sgphong
 * reference: phongn
 * description: a Phong lobe as a mobile shader writes it: a spherical Gaussian in exp2, in half
 */
// (c^n) ~ exp2(k (c - 1)) with k = n / ln 2: the spherical-Gaussian form of a lobe, whose
// exponent is linear in the cosine. Written in half as a mobile pixel shader would be.
half SphericalGaussianLobe(half NoH, half Power)
{
    half k = Power * 1.442695;
    return exp2(k * NoH - k);
}

half sgphong(half c, half n)
{
    half norm = (n + 2.0) * 0.1591549;
    return norm * SphericalGaussianLobe(c, n);
}
