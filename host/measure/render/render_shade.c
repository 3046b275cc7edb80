/* render_shade.c - shading: the host reference of a pixel (render_shade_ref), the display curve
 * and its table, and the device side (the shading and copy kernels of kernels/shade.cl). */
#define _XOPEN_SOURCE 700
#include "render_internal.h"
#include "errmsg.h"
#include "geometry.h"
#include "programs.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The model header as the host's double-precision code (for alpha(n) of the microfacet
   models); the formulas themselves are evaluated through model_eval_host. */
#define REAL double
#define RSCALAR double
#include "brdf_models.h"
#undef REAL
#undef RSCALAR

/* ------------------------------------------------------------------ shading, host side */

int render_shading_mode(const struct model_spec *m)
{
    if (model_is_full(m->info))   /* a user full BRDF: the vectors L, V, N of every pixel */
        return SHADE_USER_FULL;
    if (m->info->family == MODEL_FAMILY_MICROFACET)
        return m->info->kernel_id == BRDF_GGX ? SHADE_CT_GGX : SHADE_CT_BECKMANN;
    if (m->info->family == MODEL_FAMILY_PHYSICAL)
        return SHADE_PHYSICAL;
    return m->info->lobe == LOBE_PSI ? SHADE_LOBE_PSI : SHADE_LOBE_THETA_H;
}

int render_reference_mode(int mode, const struct model_spec *ref)
{
    return mode == SHADE_USER_FULL ? render_shading_mode(ref) : mode;
}

void render_pixel_geometry(const struct render_light *lt, const double pos[3], double v[3], double l[3], double *e)
{
    for (int c = 0; c < 3; c++)
        v[c] = lt->eye[c] - pos[c];
    vec3_normalize(v);
    if (lt->point) {
        for (int c = 0; c < 3; c++)
            l[c] = lt->light[c] - pos[c];
        double d2 = vec3_dot(l, l);
        vec3_normalize(l);
        *e = lt->intensity / d2;
    } else {
        for (int c = 0; c < 3; c++)
            l[c] = lt->light[c];
        *e = lt->intensity;
    }
}

void render_shade_ref(const struct model_spec *m, int mode, const struct render_light *lt,
                      const struct render_options *o, const double pos[3], const double nrm[3],
                      double n, double *spec, double *radiance)
{
    double v[3], l[3], e;
    render_pixel_geometry(lt, pos, v, l, &e);
    double ndotl = vec3_dot(nrm, l), ndotv = vec3_dot(nrm, v), cosine, s;
    if (mode == SHADE_LOBE_PSI) {
        double r[3];
        for (int c = 0; c < 3; c++)
            r[c] = 2.0 * ndotl * nrm[c] - l[c];
        cosine = vec3_dot(r, v);
        s = model_eval_host(m, cosine, n);
    } else {
        double h[3];
        for (int c = 0; c < 3; c++)
            h[c] = l[c] + v[c];
        vec3_normalize(h);
        cosine = vec3_dot(nrm, h);
        if (mode == SHADE_PHYSICAL)
            s = brdf_pb_eval_ud(m->info->kernel_id, ndotl, ndotv, vec3_dot(l, v), n, m->params[0], m->params[1], 0.0);
        else if (mode == SHADE_USER_FULL)
            s = model_eval_full_host(m, l, v, nrm, n);
        else
            s = model_eval_host(m, cosine, n);
        if (mode == SHADE_CT_BECKMANN || mode == SHADE_CT_GGX) {
            double vdoth = fmax(vec3_dot(v, h), 0.0);
            double fresnel = o->f0 + (1.0 - o->f0) * pow(1.0 - vdoth, 5.0);
            double alpha = brdf_alpha_from_n(n);
            double nl = fmax(ndotl, 1e-6), nv = fmax(ndotv, 1e-6);
            double g = mode == SHADE_CT_GGX
                           ? brdf_smith_g1_ggx(nl, alpha) * brdf_smith_g1_ggx(nv, alpha)
                           : brdf_smith_g1_beckmann(nl, alpha) * brdf_smith_g1_beckmann(nv, alpha);
            s = s * fresnel * g / (4.0 * nl * nv);
        }
    }
    int lit = n > 0 && ndotl > 0 && cosine > 0 && (mode < SHADE_CT_BECKMANN || ndotv > 0);
    *spec = lit ? e * ndotl * o->ks * s : 0.0;
    *radiance = e * fmax(ndotl, 0.0) * o->kd + o->ambient + *spec;
}

static unsigned char srgb8_exact(double t)
{
    t = fmin(fmax(t, 0.0), 1.0);
    double e = t <= 0.0031308 ? 12.92 * t : 1.055 * pow(t, 1.0 / 2.4) - 0.055;
    double code = floor(e * 255.0 + 0.5);
    return (unsigned char)fmin(fmax(code, 0.0), 255.0);
}

void render_display_exact(const struct render_options *o, double radiance, unsigned char rgb[3])
{
    for (int k = 0; k < 3; k++)
        rgb[k] = srgb8_exact(1.0 - exp(-o->exposure * o->tint[k] * radiance));
}

static float float_from_bits(uint32_t b)
{
    float f;
    memcpy(&f, &b, sizeof f);
    return f;
}

/* The display table the kernel indexes by (float bits >> 15) - DISPLAY_BIN0: each bin
   holds the exact colour at its geometric centre (bin 0 also takes everything below,
   down to 0, which is black). *max_code_error receives the largest difference between a
   bin's entry and the exact colour anywhere in the bin (the curve is monotone, so the
   bin's ends bound it). */
static void display_table_build(const struct render_options *o, uint32_t *table,
                                int *max_code_error)
{
    int worst = 0;
    for (int i = 0; i < DISPLAY_BINS; i++) {
        uint32_t bits = (uint32_t)(DISPLAY_BIN0 + i) << 15;
        double lo = float_from_bits(bits), hi = float_from_bits(bits + (1u << 15));
        if (i == 0)
            lo = 0.0;
        double centre = i == 0 ? 0.0 : sqrt(lo * hi);
        if (i == DISPLAY_BINS - 1)
            hi = INFINITY;
        unsigned char c[3], a[3], b[3];
        render_display_exact(o, centre, c);
        render_display_exact(o, lo, a);
        render_display_exact(o, isinf(hi) ? 1e30 : hi, b);
        for (int k = 0; k < 3; k++) {
            worst = abs((int)c[k] - (int)a[k]) > worst ? abs((int)c[k] - (int)a[k]) : worst;
            worst = abs((int)c[k] - (int)b[k]) > worst ? abs((int)c[k] - (int)b[k]) : worst;
        }
        table[i] = (uint32_t)c[0] | ((uint32_t)c[1] << 8) | ((uint32_t)c[2] << 16) | 0xff000000u;
    }
    *max_code_error = worst;
}

/* ------------------------------------------------------------------ device */

long render_work_items(const struct cl_session *s)
{
    return s->is_cpu ? RENDER_WORK_ITEMS : clsession_default_work_items(s, 1L << 20);
}

int render_device_open(struct render_device *d, struct cl_session *s,
                       const struct render_options *o, char *err, size_t errlen)
{
    int rc = 0;
    cl_int e;
    memset(d, 0, sizeof *d);
    d->s = s;
    d->global_size = (size_t)render_work_items(s);
    uint32_t *table = malloc(DISPLAY_BINS * sizeof *table);
    if (!table) {
        set_err(err, errlen, "out of memory");
        return EXIT_RUNTIME;
    }
    display_table_build(o, table, &d->display_code_error);
    static const char *const names[] = { "shade", "copy_gbuffer" };
    cl_kernel *const kernels[] = { &d->shade, &d->copy };
    rc = clsession_build_kernels(s, "shade.cl", NULL, "", &d->program, 2, names, kernels);
    if (rc) {
        set_err(err, errlen, "building kernels/shade.cl or making its kernels failed (see above)");
        free(table);
        return rc;
    }
    d->display_table = clCreateBuffer(s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                      DISPLAY_BINS * sizeof *table, table, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(display table)", fail);
    d->no_table = clCreateBuffer(s->ctx, CL_MEM_READ_ONLY, 16 * sizeof(float), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(no measured table)", fail);
    free(table);
    return 0;
fail:
    free(table);
    set_err(err, errlen, "OpenCL error while setting up the shading kernels (see above)");
    render_device_close(d);
    return rc;
}

void render_device_close(struct render_device *d)
{
    if (d->display_table)
        clReleaseMemObject(d->display_table);
    if (d->no_table)
        clReleaseMemObject(d->no_table);
    cl_kernel *const kernels[] = { &d->shade, &d->copy };
    clsession_release_kernels(&d->program, 2, kernels);
    memset(d, 0, sizeof *d);
}

/* `model`: the label the deadline's message names (NULL for the copy kernel). */
static int launch(struct render_device *d, cl_kernel k, const char *model, double *seconds)
{
    int rc = 0;
    cl_event ev = NULL;
    size_t global = d->global_size, local;
    const size_t *lp = clsession_group_size(d->s, global, &local);
    CL_CHECK_GOTO(clEnqueueNDRangeKernel(d->s->queue, k, 1, NULL, &global, lp, 0, NULL, &ev),
                  done);
    CL_CHECK_GOTO(clsession_finish(d->s, k, model), done);
    if (seconds)
        *seconds = cl_event_seconds(ev);
done:
    if (ev)
        clReleaseEvent(ev);
    return rc;
}

static void shade_params(const struct render_light *lt, const struct render_options *o,
                         cl_float16 *p)
{
    memset(p, 0, sizeof *p);   /* kernels/shade_shared.h's positions */
    for (int k = 0; k < 3; ++k) {
        p->s[SHADE_P_EYE + k] = (float)lt->eye[k];
        p->s[SHADE_P_LIGHT + k] = (float)lt->light[k];
    }
    p->s[SHADE_P_AMBIENT] = (float)o->ambient;
    p->s[SHADE_P_POINT] = lt->point ? 1.0f : 0.0f;
    p->s[SHADE_P_INTENSITY] = (float)lt->intensity;
    p->s[SHADE_P_KD] = (float)o->kd;
    p->s[SHADE_P_KS] = (float)o->ks;
    p->s[SHADE_P_F0] = (float)o->f0;
}

static int set_common_args(cl_kernel k, cl_mem gbuf, size_t stride, size_t npix, cl_mem rgba,
                           cl_mem spec)
{
    int rc = 0;
    cl_uint st = (cl_uint)stride, nch = (cl_uint)((npix + 15) / 16);
    CL_SET_ARGS_GOTO(done, k, 0, CL_ARG(gbuf), CL_ARG(st), CL_ARG(nch), CL_ARG(rgba), CL_ARG(spec));
done:
    return rc;
}

int render_device_shade(struct render_device *d, cl_mem gbuf, size_t stride, size_t npix,
                        cl_mem out_rgba, cl_mem out_spec, const struct model_spec *m, int mode,
                        const struct render_light *lt, const struct render_options *o,
                        unsigned *rgba, float *spec, double *seconds)
{
    cl_kernel shade;   /* a user model's own build of shade.cl, or the shared one */
    int rc = programs_kernel(d->s, "shade.cl", "", m, "shade", d->shade, &shade);
    if (rc)
        return rc;
    rc = set_common_args(shade, gbuf, stride, npix, out_rgba, out_spec);
    if (rc)
        return rc;
    cl_int kmode = mode, kmodel = m->info->kernel_id;
    cl_float p0 = (cl_float)m->params[0], p1 = (cl_float)m->params[1];
    cl_float16 params;
    shade_params(lt, o, &params);
    CL_SET_ARGS_GOTO(done, shade, 5, CL_ARG(kmode), CL_ARG(kmodel), CL_ARG(p0), CL_ARG(p1), CL_ARG(params));
    cl_mem merl = d->merl_table ? d->merl_table : d->no_table;
    CL_SET_ARGS_GOTO(done, shade, 10, CL_ARG(d->display_table), CL_ARG(merl));
    rc = launch(d, shade, m->label, seconds);
    if (rc)
        return rc;
    if (rgba)
        CL_CHECK_GOTO(clEnqueueReadBuffer(d->s->queue, out_rgba, CL_TRUE, 0, npix * sizeof *rgba,
                                          rgba, 0, NULL, NULL),
                      done);
    if (spec)
        CL_CHECK_GOTO(clEnqueueReadBuffer(d->s->queue, out_spec, CL_TRUE, 0, npix * sizeof *spec,
                                          spec, 0, NULL, NULL),
                      done);
done:
    return rc;
}

int device_copy(struct render_device *d, cl_mem gbuf, size_t stride, size_t npix,
                cl_mem out_rgba, cl_mem out_spec, double *seconds)
{
    int rc = set_common_args(d->copy, gbuf, stride, npix, out_rgba, out_spec);
    if (rc)
        return rc;
    return launch(d, d->copy, NULL, seconds);
}
