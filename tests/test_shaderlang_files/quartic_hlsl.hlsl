/* brdfbench-model
 * name: quartic_hlsl
 * description: (1 - k n (1 - c))^4 zeroed past its root, as HLSL writes it
 * param: k 0.01 1 0.25
 */
static const float ONE = 1.0f;

float cube(float x) { return x * x * x; }

float quartic(float c, float n, float k)
{
    float t = saturate(ONE - k * n * (1.0f - c));
    return t > 0.0h ? cube(t) * t : (float)0;
}
