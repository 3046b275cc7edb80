/* brdfbench-model
 * name: flowret
 * param: m 0 3 1 integer
 */
// a switch whose every way in returns (a default, no break, fall-through into the last return):
// the function ends there
float flowret(float c, float n, int m)
{
    float x = c;
    switch (m) {
    case 0:
        return c;
    case 1:
        x = c * c;
    default:
        return x + n;
    }
}
