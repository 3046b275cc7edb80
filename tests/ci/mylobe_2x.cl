/* brdfbench-model
 * name: mylobe
 * description: mylobe.cl with about twice its work (the planted slowdown of docs/ci.md's test)
 */
/* c^(n/2) twice, through ln and through log2: different functions, so the compiler cannot
   share them. */
REAL mylobe(REAL c, REAL n)
{
    REAL h = 0.5 * n, u = fmax(c, 1e-30);
    return exp(h * log(u)) * exp2(h * log2(u));
}
