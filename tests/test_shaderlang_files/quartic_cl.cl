/* brdfbench-model
 * name: quartic_cl
 * description: (1 - k n (1 - c))^4 zeroed past its root, in the OpenCL C form
 * param: k 0.01 1 0.25
 */
REAL quartic_cl(REAL c, REAL n, RSCALAR k)
{
    REAL t = fmax(1.0 - k * n * (1.0 - c), 0.0);
    return t * t * t * t;
}
