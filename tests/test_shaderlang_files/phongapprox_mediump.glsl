/* brdfbench-model
 * name: sgphongm
 * reference: phongn
 * description: phongapprox_half.hlsl's lobe in GLSL ES: float is mediump by default
 */
precision mediump float;

float sgLobe(float NoH, mediump float Power)
{
    float k = Power * 1.442695;
    return exp2(k * NoH - k);
}

float sgphongm(float c, float n)
{
    float norm = (n + 2.0) * 0.1591549;
    return norm * sgLobe(c, n);
}
