/* brdfbench-model
 * name: flowglsl
 * param: m 0 3 1 integer
 * param: part 0 4 0 integer
 */
// break, continue and switch in GLSL; part picks the value returned (test_shaderlang_flow.c
// computes each with the same code in C)
float flowglsl(float c, float n, int m, int part)
{
    // for: continue at i == 1, a break that depends on c
    float s = 0.0;
    for (int i = 0; i < 8; i++) {
        if (i == 1)
            continue;
        if (s > 2.0 * c)
            break;
        s += c * float(i);
    }
    // while with a break: the first k with c^k below 1/n
    float p = 1.0;
    float k = 0.0;
    while (k < 20.0) {
        if (p < 1.0 / n)
            break;
        p *= c;
        k += 1.0;
    }
    // nested loops: the inner one's break, the outer one's continue
    float q = 0.0;
    for (int a = 0; a < 4; a++) {
        if (a == 2)
            continue;
        for (int b = 0; b < 4; b++) {
            if (b > a)
                break;
            q += c + float(b);
        }
    }
    // switch: a break, a fall-through, default
    float t = 0.0;
    switch (m) {
    case 0:
        t = 1.0;
        break;
    case 1:
        t = 2.0;
    case 2:
        t += 3.0 * c;
        break;
    default:
        t = 7.0;
    }
    // a switch in a loop: break leaves the switch, continue the loop's iteration
    float u = 0.0;
    for (int j = 0; j < 5; j++) {
        switch (j) {
        case 1:
            continue;
        case 3:
            u += 10.0;
            break;
        default:
            u += c;
        }
        u += 0.5;
    }
    if (part == 0)
        return s;
    if (part == 1)
        return p + k;
    if (part == 2)
        return q;
    if (part == 3)
        return t;
    return u;
}
