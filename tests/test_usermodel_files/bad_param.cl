/* brdfbench-model
 * name: badparam
 * param: k 5 1 2
 */
REAL badparam(REAL c, REAL n, RSCALAR k) { return k * pow(c, n); }
