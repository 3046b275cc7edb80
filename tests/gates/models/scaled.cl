/* brdfbench-model
 * name: scaled
 * description: the Phong lobe times a constant k (a test model with closed-form errors)
 * param: k 0 10 2
 * reference: phong
 */

/* f = k c^n: relative error |k - 1| everywhere, absolute error |k - 1| c^n. c^n is written
   as kernels/brdf_models.h writes the Phong lobe, exp(n log c), so that k = 1 is phong itself. */
REAL scaled(REAL c, REAL n, RSCALAR k)
{
    return k * exp(n * log(c));
}
