/* brdfbench-model
 * name: arrparam
 * reference: phongn
 */
// Written for brdfbench's tests: functions taking arrays as parameters (GLSL's
// `const in vec3 v[4]`, as engine code writes area-light corners), passed by value: a copy the
// callee may write, the caller's array unchanged. Also a function with an array parameter that
// is never called, which must only parse.
float weightedSum(const in float w[3], const in vec3 p[3], float x) {
    vec3 s = vec3(0.0);
    for (int i = 0; i < 3; i++)
        s += w[i] * p[i] * x;
    return s.x + 2.0 * s.y + 3.0 * s.z;
}
float scratch(in float w[3]) {
    w[0] = w[0] * 10.0;   // the callee's copy
    return w[0] + w[1] + w[2];
}
float unused(const in vec2 corners[2], mat2 m) { return dot(m * corners[0], corners[1]); }
float arrparam(float c, float n) {
    float w[3] = float[3](c, n, 1.0);
    vec3 p[3] = vec3[3](vec3(1.0, 0.0, 0.0), vec3(0.0, c, 0.0), vec3(0.5, 0.25, n));
    float a = weightedSum(w, p, 2.0);
    float b = scratch(w);
    return a + b + w[0];
}
