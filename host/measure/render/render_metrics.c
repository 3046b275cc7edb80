/* render_metrics.c - an image against its reference: the error metrics and error image, and
 * the check of the device's pixels against the double host reference on a sample. */
#define _XOPEN_SOURCE 700
#include "render_internal.h"
#include "geometry.h"
#include "raster.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------ metrics */

/* Error, metrics and the error pictures for rows [y0, y1). errimg: (y1-y0) x w floats of
   |model - reference|; signed_img (NULL: none) the same of model - reference. */
void compute_metrics(const struct gbuffer *g, int y0, int y1, const unsigned *rgba_m,
                     const float *spec_m, const unsigned *rgba_r, const float *spec_r,
                     double threshold, float *errimg, float *signed_img, struct image_metrics *mt)
{
    const float *sh = gbuffer_plane(g, GB_SHIN);
    const int w = g->width;
    memset(mt, 0, sizeof *mt);
    mt->max_x = mt->max_y = -1;
    double sum = 0, sum2 = 0, sq8 = 0;
    size_t above = 0;
    for (int y = y0; y < y1; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * w + x;
            float *out = errimg + (size_t)(y - y0) * w + x;
            float *sgn = signed_img ? signed_img + (size_t)(y - y0) * w + x : NULL;
            if (!(sh[i] > 0)) {
                *out = NAN;
                if (sgn) *sgn = NAN;
                continue;
            }
            double d = (double)spec_m[i] - (double)spec_r[i], e = fabs(d);
            *out = (float)e;
            if (sgn) *sgn = (float)d;
            mt->pixels++;
            if (!isfinite(e)) {
                mt->nonfinite++;   /* a NaN would pass every comparison below unseen */
                continue;
            }
            sum += e;
            sum2 += e * e;
            above += e > threshold;
            if (e > mt->max_abs || mt->max_x < 0) {
                mt->max_abs = e;
                mt->max_x = x;
                mt->max_y = y;
            }
            if (spec_r[i] > mt->peak_reference)
                mt->peak_reference = spec_r[i];
            for (int k = 0; k < 3; k++) {
                double d = (double)((rgba_m[i] >> (8 * k)) & 255u) -
                           (double)((rgba_r[i] >> (8 * k)) & 255u);
                sq8 += d * d;
            }
        }
    if (mt->pixels) {
        mt->mean_abs = sum / mt->pixels;
        mt->rmse = sqrt(sum2 / mt->pixels);
        mt->share_above = (double)above / mt->pixels;
        double mse8 = sq8 / (3.0 * mt->pixels);
        mt->psnr_db = mse8 > 0 ? 10.0 * log10(255.0 * 255.0 / mse8) : NAN;
    } else {
        mt->psnr_db = NAN;
    }
}

void render_worst_pixel(const struct gbuffer *g, const struct render_light *lt, const struct image_metrics *mt,
                        const float *spec_m, const float *spec_r, struct render_worst_pixel *wp)
{
    memset(wp, 0, sizeof *wp);
    if (mt->max_x < 0 || mt->nonfinite)
        return;
    size_t i = (size_t)mt->max_y * g->width + mt->max_x;
    double pos[3];
    for (int c = 0; c < 3; c++) {
        pos[c] = gbuffer_plane(g, GB_PX + c)[i];
        wp->N[c] = gbuffer_plane(g, GB_NX + c)[i];
    }
    render_pixel_geometry(lt, pos, wp->V, wp->L, &wp->e);   /* as render_shade_ref and the kernel take them */
    wp->n = gbuffer_plane(g, GB_SHIN)[i];
    wp->x = mt->max_x;
    wp->y = mt->max_y;
    wp->spec_model = spec_m[i];
    wp->spec_reference = spec_r[i];
    wp->valid = 1;
}

/* One pixel of the device's output against the double reference. */
static void check_pixel(const struct gbuffer *g, size_t pi, const struct model_spec *m, int mode,
                        const struct render_light *lt, const struct render_options *o,
                        const unsigned *rgba, const float *spec, struct reference_check *rc)
{
    double pos[3] = {gbuffer_plane(g, GB_PX)[pi], gbuffer_plane(g, GB_PY)[pi],
                     gbuffer_plane(g, GB_PZ)[pi]};
    double nrm[3] = {gbuffer_plane(g, GB_NX)[pi], gbuffer_plane(g, GB_NY)[pi],
                     gbuffer_plane(g, GB_NZ)[pi]};
    double s_ref, rad_ref;
    render_shade_ref(m, mode, lt, o, pos, nrm, gbuffer_plane(g, GB_SHIN)[pi], &s_ref, &rad_ref);
    double d = fabs((double)spec[pi] - s_ref);
    if (d > rc->max_abs || rc->samples == 0) {
        rc->max_abs = d;
        rc->value_at_max = s_ref;
    }
    rc->peak = fmax(rc->peak, s_ref);
    unsigned char exact[3];
    render_display_exact(o, rad_ref, exact);
    for (int c = 0; c < 3; c++) {
        int dc = abs((int)((rgba[pi] >> (8 * c)) & 255u) - (int)exact[c]);
        if (dc > rc->max_code)
            rc->max_code = dc;
    }
    rc->samples++;
}

/* The device's specular radiance and colours against the double reference on up to
   o->ref_samples foreground pixels of rows [y0, y1), spread evenly, plus the brightest
   (the highlight's peak, where the lobe matters most). */
struct check_ctx {
    const struct gbuffer *g;
    int y0, y1;
    const struct model_spec *m;
    int mode;
    const struct render_light *lt;
    const struct render_options *o;
    const unsigned *rgba;
    const float *spec;
};

static void check_reference_in(void *vctx, void *vout);

void check_reference(const struct gbuffer *g, int y0, int y1, const struct model_spec *m,
                     int mode, const struct render_light *lt, const struct render_options *o,
                     const unsigned *rgba, const float *spec, struct reference_check *rc)
{
    /* in one sandbox for a user model's code (model_run_isolated), not a round trip to it per
       pixel; a sandbox that fails stops the run there (usermodel_isolated) */
    const struct check_ctx c = { g, y0, y1, m, mode, lt, o, rgba, spec };
    memset(rc, 0, sizeof *rc);
    (void)model_run_isolated(m, check_reference_in, (void *)&c, rc, sizeof *rc);
}

static void check_reference_in(void *vctx, void *vout)
{
    const struct check_ctx *c = vctx;
    const struct gbuffer *g = c->g;
    int y0 = c->y0, y1 = c->y1, mode = c->mode;
    const struct model_spec *m = c->m;
    const struct render_light *lt = c->lt;
    const struct render_options *o = c->o;
    const unsigned *rgba = c->rgba;
    const float *spec = c->spec;
    struct reference_check *rc = vout;
    const float *sh = gbuffer_plane(g, GB_SHIN);
    memset(rc, 0, sizeof *rc);
    size_t first = (size_t)y0 * g->width, last = (size_t)y1 * g->width, fg = 0;
    size_t brightest = last;
    for (size_t i = first; i < last; i++)
        if (sh[i] > 0) {
            fg++;
            if (brightest == last || spec[i] > spec[brightest])
                brightest = i;
        }
    if (fg == 0)
        return;
    size_t want = o->ref_samples > 0 ? (size_t)o->ref_samples : 1;
    size_t step = fg > want ? fg / want : 1, k = 0;
    for (size_t i = first; i < last; i++)
        if (sh[i] > 0 && k++ % step == 0)
            check_pixel(g, i, m, mode, lt, o, rgba, spec, rc);
    check_pixel(g, brightest, m, mode, lt, o, rgba, spec, rc);
    rc->relative_to_peak = rc->max_abs / fmax(rc->peak, 1e-30);
    /* Float shading carries the lobe cosine to a few float ulps (1 ulp = 6e-8 near 1); a
       lobe's relative change per unit of cosine is about n for c^n and the quadratics and
       2(n+2) for GGX near its peak, so with n <= 1000 and 8 ulps the specular radiance
       agrees to 8 * 6e-8 * 2002 = 1e-3 of the peak. */
    rc->bound = 1e-3 * fmax(rc->peak, 1e-6);
    rc->within = rc->max_abs <= rc->bound && rc->max_code <= 2;
}
