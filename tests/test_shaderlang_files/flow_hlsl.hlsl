/* brdfbench-model
 * name: flowhlsl
 * param: m 0 5 2 integer
 */
// do/while with continue and break, a switch with grouped labels and default first, in HLSL
float flowhlsl(float c, float n, int m)
{
    float s = 0.0;
    float k = 0.0;
    [loop] do {
        k += 1.0;
        if (k == 2.0)
            continue;          // to the condition: k == 2 adds nothing
        if (s * n > 40.0)
            break;
        s += c * k;
    } while (k < 6.0);
    float w = 0.0;
    [branch] switch (m) {
    default:
        w = -1.0;
        break;
    case 1:
    case 2:
        w = saturate(c * 2.0);
        break;
    case 4:
        w = lerp(c, 1.0, 0.25);
    }
    return s + 100.0 * w;
}
