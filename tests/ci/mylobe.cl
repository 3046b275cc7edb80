/* brdfbench-model
 * name: mylobe
 * description: the Phong lobe as exp(n ln c): the user lobe of docs/ci.md's pipeline test
 */
REAL mylobe(REAL c, REAL n)
{
    return exp(n * log(fmax(c, 1e-30)));
}
