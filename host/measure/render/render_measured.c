/* render_measured.c - a mesh shaded with a measured material (MERL table, render --measured)
 * beside the same mesh shaded with the lobes fitted to it by host/measure/measured/measured.c: Blinn-Phong
 * ks cos^n(theta_h) + kd and Cook-Torrance Beckmann / GGX kd + ks D F G / (4 N.L N.V) at their
 * fitted roughness and F0. Every image is the radiance E (N.L) f of the whole BRDF (the
 * measured table holds the diffuse part too, so the pass's own diffuse and ambient terms are
 * off and a fit's Lambertian term kd takes their place), lit where L and V lie above the
 * surface. Error images: |fit - measured| per pixel. The device's lookup is checked against
 * the host's (merl_luminance) on sampled pixels. */
#include "render.h"
#include "render_report.h"

#include "draw.h"
#include "exitcodes.h"
#include "measured.h"
#include "outdir.h"
#include "raster.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CHECK_PIXELS 4096

/* The entries' models and options: the measured table, then the fits (measured.h's order). */
static int entry_setup(int k, const struct measured_material *mm, const struct render_options *o,
                       struct render_measured_entry *en, struct model_spec *spec, int *mode,
                       struct render_options *oo)
{
    *oo = *o;
    oo->ambient = 0;
    oo->kd = 0;
    oo->ks = 1;
    if (k == 0) {
        snprintf(en->label, sizeof en->label, "measured");
        model_spec_default(models_find("phong"), spec);   /* unused by the lookup */
        *mode = SHADE_MEASURED;
        en->fitted = 1;
        en->n = en->ks = en->kd = en->f0 = NAN;
        return 0;
    }
    const struct measured_fit *f = &mm->fit[k - 1];
    en->fitted = f->ok && isfinite(f->n) && f->n > 0;
    en->n = f->n;
    en->ks = f->ks;
    en->kd = f->kd;
    en->f0 = f->f0;
    snprintf(en->label, sizeof en->label, "%s fit", measured_fit_name[k - 1]);
    oo->ks = f->ks;
    oo->kd = f->kd;
    if (k == 1) {
        model_spec_default(models_find("blinn"), spec);
        *mode = SHADE_LOBE_THETA_H;
        return 0;
    }
    char text[96], err[256];
    snprintf(text, sizeof text, "%s:F0=%.9g", k == 2 ? "ct-beckmann" : "ct-ggx", isfinite(f->f0) ? f->f0 : 0.5);
    *mode = SHADE_PHYSICAL;
    return model_spec_parse(text, spec, err, sizeof err) ? -1 : 0;
}

/* Radiance of an entry at every pixel: the kernel's specular output plus the fit's Lambertian
 * term, where the pixel is lit (ed: E (N.L), 0 where L or V is below the surface). */
static void radiance_of(const float *spec, const double *ed, size_t npix, double kd, double *rad)
{
    for (size_t i = 0; i < npix; ++i)
        rad[i] = ed[i] > 0 ? spec[i] + (isfinite(kd) ? kd : 0.0) * ed[i] : 0.0;
}

/* E (N.L) of every pixel where L and V lie above the surface, else 0; and the host's check of
 * the measured entry on a stride of pixels. */
static void pixel_irradiance(const struct gbuffer *g, const struct render_light *lt, const struct merl_material *mat,
                             const float *spec_meas, double *ed, struct render_measured_result *res)
{
    const float *sh = gbuffer_plane(g, GB_SHIN);
    size_t stride = g->npix / CHECK_PIXELS + 1;
    double worst = 0, peak = 0;
    res->check_pixels = 0;
    for (size_t i = 0; i < g->npix; ++i) {
        double pos[3], nrm[3], v[3], l[3], e;
        for (int c = 0; c < 3; ++c) {
            pos[c] = gbuffer_plane(g, GB_PX + c)[i];
            nrm[c] = gbuffer_plane(g, GB_NX + c)[i];
        }
        render_pixel_geometry(lt, pos, v, l, &e);
        double nl = nrm[0] * l[0] + nrm[1] * l[1] + nrm[2] * l[2], nv = nrm[0] * v[0] + nrm[1] * v[1] + nrm[2] * v[2];
        ed[i] = sh[i] > 0 && nl > 0 && nv > 0 ? e * nl : 0;
        if (ed[i] > 0 && i % stride == 0) {
            double host = ed[i] * merl_luminance(mat, l, v, nrm);
            worst = fmax(worst, fabs(host - spec_meas[i]));
            peak = fmax(peak, host);
            res->check_pixels++;
        }
    }
    res->check_max_abs_of_peak = peak > 0 ? worst / peak : (worst > 0 ? INFINITY : 0);
}

static int write_pictures(const char *scene_dir, const char *mat, const struct render_measured_entry *en, int w,
                          int h, const unsigned char *rgb_meas, const unsigned char *rgb, const float *errimg,
                          const float *signed_img, float vmax, int first, char *err, size_t errlen)
{
    char path[4400], name[400], title[512];
    char base[96];
    snprintf(base, sizeof base, "%s", en->label);
    for (char *p = base; *p; ++p)
        if (*p == ' ')
            *p = '_';
    if (first) {
        snprintf(name, sizeof name, "measured_%s.png", mat);
        path_join(path, sizeof path, scene_dir, name);
        return draw_png_rgb8(path, w, h, rgb_meas, err, errlen);
    }
    snprintf(name, sizeof name, "measured_%s_%s.png", mat, base);
    path_join(path, sizeof path, scene_dir, name);
    if (draw_png_rgb8(path, w, h, rgb, err, errlen))
        return EXIT_RUNTIME;
    snprintf(name, sizeof name, "measured_%s_%s_error.png", mat, base);
    path_join(path, sizeof path, scene_dir, name);
    snprintf(title, sizeof title, "%s: |%s - measured| radiance (max %.3g)", mat, en->label, en->max_abs);
    if (draw_error_image(path, w, h, errimg, vmax, title, err, errlen))
        return EXIT_RUNTIME;
    snprintf(name, sizeof name, "measured_%s_%s_signed_error.png", mat, base);
    path_join(path, sizeof path, scene_dir, name);
    snprintf(title, sizeof title, "%s: %s - measured radiance\nblue: the fit under the measurement, red: over; scale +-%.3g",
             mat, en->label, en->max_abs);
    if (draw_signed_error_image(path, w, h, signed_img, (float)en->max_abs, title, err, errlen))
        return EXIT_RUNTIME;
    snprintf(name, sizeof name, "measured_%s_%s_contact.png", mat, base);
    path_join(path, sizeof path, scene_dir, name);
    snprintf(title, sizeof title, "%s: measured | %s | error (max %.3g)", mat, en->label, en->max_abs);
    return draw_contact_sheet(path, w, h, rgb_meas, rgb, errimg, vmax, title, err, errlen) ? EXIT_RUNTIME : 0;
}

int render_measured_pass(struct render_device *dev, const struct gbuffer *g, const struct render_light *lt,
                         const struct render_options *o, const struct merl_material *mat, const char *scene_dir,
                         struct render_measured_result *res, char *err, size_t errlen)
{
    struct cl_session *s = dev->s;
    const size_t npix = g->npix;
    int rc = 0;
    cl_int e;
    cl_mem gbuf = NULL, out_rgba = NULL, out_spec = NULL;
    struct measured_material *mm = calloc(1, sizeof *mm);
    unsigned *rgba = malloc(npix * sizeof *rgba);
    float *spec = malloc(npix * sizeof *spec), *spec_meas = malloc(npix * sizeof *spec_meas);
    float *errimg = malloc(npix * sizeof *errimg), *shin = malloc(g->stride * sizeof *shin);
    float *signed_img = malloc(npix * sizeof *signed_img);
    double *ed = malloc(npix * sizeof *ed), *rad_meas = malloc(npix * sizeof *rad_meas);
    double *rad = malloc(npix * sizeof *rad);
    unsigned char *rgb_meas = malloc(npix * 3), *rgb = malloc(npix * 3);
    memset(res, 0, sizeof *res);
    snprintf(res->material, sizeof res->material, "%s", mat->name);
    if (!mm || !rgba || !spec || !spec_meas || !errimg || !signed_img || !shin || !ed || !rad_meas || !rad || !rgb_meas || !rgb) {
        snprintf(err, errlen, "%s: out of memory for the measured comparison", mat->name);
        rc = EXIT_RUNTIME;
        goto done;
    }
    struct measured_options mo;
    measured_options_default(&mo);
    mo.nlobes = 0;
    mo.io.quiet = 1;
    if ((rc = measured_material_run(s, mat, &mo, mm)) != 0 || (rc = merl_table_buffer(s, mat, &dev->merl_table)))
        goto done;
    gbuf = clCreateBuffer(s->ctx, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, g->stride * GB_NPLANES * sizeof(float),
                          g->data, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(measured G-buffer)", done);
    out_rgba = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, g->stride * sizeof(cl_uint), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(measured rgba)", done);
    out_spec = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, g->stride * sizeof(float), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(measured spec)", done);
    const float *sh = gbuffer_plane(g, GB_SHIN);
    for (int k = 0; k < RENDER_MEASURED_ENTRIES; ++k) {
        struct render_measured_entry *en = &res->e[res->count++];
        struct model_spec spec_k;
        struct render_options oo;
        int mode;
        if (entry_setup(k, mm, o, en, &spec_k, &mode, &oo)) {
            snprintf(err, errlen, "%s: the %s fit has no model", mat->name, measured_fit_name[k - 1]);
            rc = EXIT_RUNTIME;
            goto done;
        }
        if (!en->fitted)
            continue;
        /* the fit's shininess (Cook-Torrance: alpha's n) on every foreground pixel */
        for (size_t i = 0; i < g->stride; ++i)
            shin[i] = i < npix && sh[i] > 0 ? (float)(k == 0 ? 1.0 : en->n) : 0.0f;
        CL_CHECK_GOTO(clEnqueueWriteBuffer(s->queue, gbuf, CL_TRUE, GB_SHIN * g->stride * sizeof(float),
                                           g->stride * sizeof(float), shin, 0, NULL, NULL), done);
        if ((rc = render_device_shade(dev, gbuf, g->stride, npix, out_rgba, out_spec, &spec_k, mode, lt, &oo, rgba,
                                      k == 0 ? spec_meas : spec, NULL)) != 0)
            goto done;
        if (k == 0) {
            pixel_irradiance(g, lt, mat, spec_meas, ed, res);
            radiance_of(spec_meas, ed, npix, NAN, rad_meas);
            for (size_t i = 0; i < npix; ++i)
                res->peak = fmax(res->peak, rad_meas[i]);
            render_rgba_to_rgb(rgba, npix, rgb_meas);
        } else {
            radiance_of(spec, ed, npix, en->kd, rad);
            double sum = 0;
            long cnt = 0;
            for (size_t i = 0; i < npix; ++i) {
                double d = sh[i] > 0 ? fabs(rad[i] - rad_meas[i]) : 0;
                errimg[i] = (float)d;
                signed_img[i] = sh[i] > 0 ? (float)(rad[i] - rad_meas[i]) : NAN;   /* background: no data */
                en->max_abs = fmax(en->max_abs, d);
                sum += d * d;
                cnt += sh[i] > 0;
            }
            en->rms = cnt ? sqrt(sum / (double)cnt) : 0;
            render_rgba_to_rgb(rgba, npix, rgb);
        }
        if (o->write_images &&
            (rc = write_pictures(scene_dir, mat->name, en, g->width, g->height, rgb_meas, rgb, errimg, signed_img,
                                 (float)fmax(res->peak * 0.25, 1e-12), k == 0, err, errlen)) != 0)
            goto done;
    }
done:;
    cl_mem made[4] = { out_spec, out_rgba, gbuf, dev->merl_table };
    for (int i = 0; i < 4; ++i)
        if (made[i])
            clReleaseMemObject(made[i]);
    dev->merl_table = NULL;
    free(mm);
    free(rgba);
    free(spec);
    free(spec_meas);
    free(errimg);
    free(signed_img);
    free(shin);
    free(ed);
    free(rad_meas);
    free(rad);
    free(rgb_meas);
    free(rgb);
    if (rc && !err[0])
        snprintf(err, errlen, "%s: the measured comparison failed (see above)", mat->name);
    return rc;
}
