/* brdfbench-model
 * name: myquad
 * description: the affine cosine-quadratic ((a n + b)(c - 1) + 1)^2, zeroed past its root
 * param: a 0 2 0.448
 * param: b -2 2 0.099
 */
REAL myquad(REAL c, REAL n, RSCALAR a, RSCALAR b)
{
    /* Branch-free, so the same text compiles for float16, float and double. */
    REAL base = fmax((a * n + b) * (c - 1.0) + 1.0, 0.0);
    return base * base;
}
