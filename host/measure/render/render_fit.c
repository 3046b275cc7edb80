/* render_fit.c - He against the lobes: the least-squares fit of Blinn-Phong to He's specular
 * radiance (render_he_fit) and the pass that shades a mesh by He's model and by each lobe at
 * the fitted n, with their error images. */
#define _XOPEN_SOURCE 700
#include "render_internal.h"
#include "render_pictures.h"
#include "errmsg.h"
#include "draw.h"
#include "exitcodes.h"
#include "outdir.h"
#include "raster.h"
#include "refine.h"
#include "render_report.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The model header in double: the kernel ids of the lobes. */
#define REAL double
#define RSCALAR double
#include "brdf_models.h"
#undef REAL
#undef RSCALAR

/* ------------------------------------------------------------------ He against the lobes */

/* The least-squares fit of Blinn-Phong k A_i c_i^n to He's specular radiance h_i over the
   foreground: for each n the best k is sum(b h) / sum(b b) (b_i = A_i c_i^n), leaving the
   residual sum(h h) - sum(b h)^2 / sum(b b); n minimises it. */
struct he_fit {
    size_t count;
    double *a, *c, *h;     /* E (N.L) ks, N.H, He's specular radiance */
    double hh;
};
static double he_fit_residual(double u, void *ctx)
{
    const struct he_fit *f = ctx;
    double n = exp(u), bh = 0, bb = 0;
    for (size_t i = 0; i < f->count; i++) {
        double b = f->a[i] * exp(n * log(f->c[i]));
        bh += b * f->h[i];
        bb += b * b;
    }
    return bb > 0 ? f->hh - bh * bh / bb : f->hh;
}
static double he_fit_scale(const struct he_fit *f, double n)
{
    double bh = 0, bb = 0;
    for (size_t i = 0; i < f->count; i++) {
        double b = f->a[i] * exp(n * log(f->c[i]));
        bh += b * f->h[i];
        bb += b * b;
    }
    return bb > 0 ? bh / bb : 0;
}

void render_he_fit(const double *a, const double *c, const double *h, size_t count, double *n, double *k,
                   double *rel_rms)
{
    struct he_fit fit = { count, (double *)a, (double *)c, (double *)h, 0 };
    for (size_t i = 0; i < count; i++)
        fit.hh += h[i] * h[i];
    double u = log(64.0);
    if (count == 0 || brent_minimum(he_fit_residual, &fit, log(1.0), log(64.0), log(20000.0), 1e-9, 1e-9, 200, &u) != 0) {
        /* a scan when Brent's bracket does not hold (the minimum near an end of [1, 20000]) */
        double best = INFINITY;
        for (double t = log(1.0); t <= log(20000.0); t += 0.002) {
            double r = he_fit_residual(t, &fit);
            if (r < best) {
                best = r;
                u = t;
            }
        }
    }
    *n = exp(u);
    *k = he_fit_scale(&fit, *n);
    *rel_rms = fit.hh > 0 ? sqrt(fmax(he_fit_residual(u, &fit), 0.0) / fit.hh) : NAN;
}

/* Writes an entry's error image against He's and, when `all_pictures`, its image and the
   contact sheet He | entry | error (PNG writing is most of this pass's time, so the other
   cheap lobes get the error image only). */
static int he_pictures(const char *scene_dir, const char *sc, const char *base, int w, int h, const unsigned *rgba,
                       const unsigned char *rgb_he, unsigned char *rgb, const float *errimg, const float *signed_img,
                       struct he_entry *en, const char *he_label, int all_pictures, char *err, size_t errlen)
{
    char title[400], ctitle[400], stitle[400];
    if (all_pictures)
        render_rgba_to_rgb(rgba, (size_t)w * h, rgb);
    snprintf(title, sizeof title, "%s: |%s - %s| specular radiance, max %.3g mean %.3g", sc, en->label, he_label,
             en->metrics.max_abs, en->metrics.mean_abs);
    snprintf(ctitle, sizeof ctitle, "%s: %s | %s | error (max %.3g)", sc, he_label, en->label, en->metrics.max_abs);
    render_signed_title(stitle, sizeof stitle, sc, en->label, he_label, en->metrics.max_abs);
    struct render_picture_set ps = {scene_dir, sc, "he_", base, w, h, all_pictures ? rgb : NULL,
                                    all_pictures ? rgb_he : NULL, errimg, signed_img, en->metrics.max_abs, title,
                                    stitle, ctitle, en->image, en->error, en->signed_error, en->contact};
    return render_write_pictures(&ps, err, errlen);
}

/* The host images of the He pass: He's, Blinn-Phong's at the fitted n and the entry's being
   shaded, with the error images and the 8-bit colours. */
struct he_images {
    unsigned *rgba_he, *rgba_b, *rgba_m;
    float *spec_he, *spec_b, *spec_m, *errimg, *signed_img;
    unsigned char *rgb_he, *rgb;
};

/* The pass's images and the fit's inputs, npix pixels each. */
static struct pixel_buffers he_buffers(struct he_images *im, struct he_fit *fit)
{
    return (struct pixel_buffers){
        .rgba = { &im->rgba_he, &im->rgba_b, &im->rgba_m },
        .floats = { &im->spec_he, &im->spec_b, &im->spec_m, &im->errimg, &im->signed_img },
        .doubles = { &fit->a, &fit->c, &fit->h },
        .rgb = { &im->rgb_he, &im->rgb },
    };
}

/* Allocates the pass's images and the fit's inputs for npix pixels; -1 when out of memory
   (what was allocated is freed by he_free). */
static int he_alloc(struct he_images *im, struct he_fit *fit, size_t npix)
{
    struct pixel_buffers b = he_buffers(im, fit);
    return pixel_buffers_alloc(&b, npix);
}

static void he_free(struct he_images *im, struct he_fit *fit)
{
    struct pixel_buffers b = he_buffers(im, fit);
    pixel_buffers_free(&b);
}

/* The fit's inputs: every lit foreground pixel, in double from the G-buffer, with He's
   specular radiance there. */
static void he_fit_inputs(const struct gbuffer *g, const struct render_light *lt, const struct render_options *o,
                          const struct model_spec *blinn, const float *spec_he, struct he_fit *fit)
{
    const float *px = gbuffer_plane(g, GB_PX), *py = gbuffer_plane(g, GB_PY), *pz = gbuffer_plane(g, GB_PZ);
    const float *nx = gbuffer_plane(g, GB_NX), *ny = gbuffer_plane(g, GB_NY), *nz = gbuffer_plane(g, GB_NZ);
    const float *sh = gbuffer_plane(g, GB_SHIN);
    for (size_t i = 0; i < g->npix; i++) {
        if (!(sh[i] > 0))
            continue;
        double pos[3] = { px[i], py[i], pz[i] }, nrm[3] = { nx[i], ny[i], nz[i] }, spec1, rad;
        /* Blinn-Phong at n = 1 gives E (N.L) ks c; with it and c the lobe at any n is A c^n */
        render_shade_ref(blinn, SHADE_LOBE_THETA_H, lt, o, pos, nrm, 1.0, &spec1, &rad);
        double v[3], l[3], hv[3];
        for (int k = 0; k < 3; k++) {
            v[k] = lt->eye[k] - pos[k];
            l[k] = lt->point ? lt->light[k] - pos[k] : lt->light[k];
        }
        vec3_normalize(v);
        vec3_normalize(l);
        for (int k = 0; k < 3; k++)
            hv[k] = l[k] + v[k];
        vec3_normalize(hv);
        double c = vec3_dot(nrm, hv);
        if (!(spec1 > 0 && c > 0))
            continue;
        fit->a[fit->count] = spec1 / c;
        fit->c[fit->count] = c;
        fit->h[fit->count] = spec_he[i];
        fit->hh += (double)spec_he[i] * spec_he[i];
        fit->count++;
    }
}

/* Writes He's image of the scene (he_<label>.png) and records its path in hc->he_image. */
static int he_write_image(const char *scene_dir, const char *sc, int w, int h, const unsigned char *rgb_he,
                          struct he_comparison *hc, char *err, size_t errlen)
{
    char base[MODEL_LABEL_MAX + 8], name[300], path[4600];
    label_to_file(hc->he.label, base, sizeof base);
    snprintf(name, sizeof name, "he_%s.png", base);
    snprintf(hc->he_image, sizeof hc->he_image, "render/%s/he_%s.png", sc, base);
    path_join(path, sizeof path, scene_dir, name);
    return draw_png_rgb8(path, w, h, rgb_he, err, errlen) != 0 ? EXIT_RUNTIME : 0;
}

/* A mesh shaded by He's model (o->he_material), then by Blinn-Phong at the n (and scale) that
   fits He's specular radiance best, and by each cheap lobe of the run (quadratic and rational
   families) at that n in the Blinn variable; error images against He's. */
int he_pass(struct render_device *dev, const struct scene_data *sd, const struct render_options *o,
            const char *stage_dir, struct scene_result *res, char *err, size_t errlen)
{
    struct cl_session *s = dev->s;
    struct he_comparison *hc = &res->he;
    const int w = o->width, h = o->height;
    const char *sc = render_scene_names[sd->kind];
    struct gbuffer g;
    struct render_light lt;
    struct he_fit fit = {0};
    cl_mem gbuf = NULL, out_rgba = NULL, out_spec = NULL;
    struct he_images im = {0};
    int rc = 0;
    char text[64];
    memset(hc, 0, sizeof *hc);
    snprintf(text, sizeof text, "he:material=%d", o->he_material);
    if (model_spec_parse(text, &hc->he, err, errlen))
        return EXIT_USAGE;
    if ((rc = scene_gbuffer(sd, o, w, h, &g, &lt, err, errlen)) != 0)
        return rc;
    const size_t npix = g.npix;
    if ((rc = pass_buffers(s, &g, CL_MEM_READ_WRITE, "He ", &gbuf, &out_rgba, &out_spec)))
        goto fail;
    if (he_alloc(&im, &fit, npix) != 0) {
        set_err(err, errlen, "%s: out of memory for the He comparison", sc);
        rc = EXIT_RUNTIME;
        goto done;
    }
    if ((rc = render_device_shade(dev, gbuf, g.stride, npix, out_rgba, out_spec, &hc->he, SHADE_PHYSICAL, &lt, o,
                                  im.rgba_he, im.spec_he, NULL)) != 0)
        goto fail;
    float *sh = gbuffer_plane(&g, GB_SHIN);
    struct model_spec blinn;
    model_spec_default(models_find("blinn"), &blinn);
    he_fit_inputs(&g, &lt, o, &blinn, im.spec_he, &fit);
    hc->fit_pixels = fit.count;
    render_he_fit(fit.a, fit.c, fit.h, fit.count, &hc->n_fit, &hc->k_fit, &hc->rel_rms);
    /* the fitted n in the G-buffer's shininess plane, ks scaled by k */
    for (size_t i = 0; i < npix; i++)
        if (sh[i] > 0)
            sh[i] = (float)hc->n_fit;
    CL_CHECK_GOTO(clEnqueueWriteBuffer(s->queue, gbuf, CL_TRUE, GB_SHIN * g.stride * sizeof(float),
                                       g.stride * sizeof(float), sh, 0, NULL, NULL),
                  fail);
    struct render_options of = *o;
    of.ks = o->ks * hc->k_fit;

    char scene_dir[4200];
    path_join(scene_dir, sizeof scene_dir, stage_dir, sc);
    if (o->write_images && outdir_prepare(scene_dir, NULL, err, errlen) != 0) {
        rc = EXIT_RUNTIME;
        goto done;
    }
    render_rgba_to_rgb(im.rgba_he, npix, im.rgb_he);
    if (o->write_images && (rc = he_write_image(scene_dir, sc, w, h, im.rgb_he, hc, err, errlen)) != 0)
        goto done;
    /* entry 0: Blinn-Phong at the fitted n; then the cheap lobes at that n */
    hc->count = 0;
    for (int mi = -1; mi < o->nmodels && hc->count < RENDER_MAX_MODELS + 1; mi++) {
        const struct model_spec *m = mi < 0 ? &blinn : &o->models[mi];
        if (mi >= 0 && m->info->family != MODEL_FAMILY_QUADRATIC && m->info->family != MODEL_FAMILY_RATIONAL)
            continue;
        struct he_entry *en = &hc->e[hc->count];
        unsigned *rg = mi < 0 ? im.rgba_b : im.rgba_m;
        float *sp = mi < 0 ? im.spec_b : im.spec_m;
        if ((rc = render_device_shade(dev, gbuf, g.stride, npix, out_rgba, out_spec, m, SHADE_LOBE_THETA_H, &lt, &of,
                                      rg, sp, NULL)) != 0)
            goto fail;
        snprintf(en->label, sizeof en->label, "%s@n=%.4g", m->label, hc->n_fit);
        compute_metrics(&g, 0, h, rg, sp, im.rgba_he, im.spec_he, o->threshold, im.errimg, im.signed_img,
                        &en->metrics);
        en->max_abs_vs_blinn = 0;
        for (size_t i = 0; i < npix; i++)
            if (sh[i] > 0)
                en->max_abs_vs_blinn = fmax(en->max_abs_vs_blinn, fabs((double)sp[i] - (double)im.spec_b[i]));
        if (o->write_images) {
            char base[MODEL_LABEL_MAX + 8];
            label_to_file(m->label, base, sizeof base);
            int all_pictures = mi < 0 || m->info->kernel_id == BRDF_FQ2;
            if ((rc = he_pictures(scene_dir, sc, base, w, h, rg, im.rgb_he, im.rgb, im.errimg, im.signed_img, en,
                                  hc->he.label, all_pictures, err, errlen)) != 0)
                goto done;
        }
        hc->count++;
    }
    hc->done = 1;
    if (!o->io.quiet)
        render_print_he(sd->kind, hc);
    goto done;
fail:
    if (!err[0])
        set_err(err, errlen, "%s: OpenCL error in the He comparison (see above)", sc);
    rc = rc ? rc : EXIT_RUNTIME;
done:
    he_free(&im, &fit);
    pass_release(out_spec, out_rgba, gbuf, &g);
    return rc;
}
