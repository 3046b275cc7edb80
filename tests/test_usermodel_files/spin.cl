/* brdfbench-model
 * name: spin
 * description: a loop that never ends (tests/test_deadline.sh: a launch past its deadline)
 */
REAL spin(REAL c, REAL n)
{
    REAL x = c;
    while (any(x > RSPLAT(-1.0)))
        x = x * RC(1.0);
    return x;
}
