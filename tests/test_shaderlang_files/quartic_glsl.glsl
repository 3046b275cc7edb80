/* brdfbench-model
 * name: quartic_glsl
 * description: (1 - k n (1 - c))^4 zeroed past its root, as GLSL writes it
 * param: k 0.01 1 0.25
 */
#version 330
float quartic(float c, float n, float k)
{
    float t = 1.0 - k * n * (1.0 - c);
    if (t < 0.0) {
        t = 0.0;
    }
    vec2 tt = vec2(t, t * t);       // a vector, taken apart again: ((t t) t) t
    return tt.y * tt.x * tt.x;
}
