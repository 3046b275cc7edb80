/* render_images.c - the image pass of a scene: every model and its reference shaded once per
 * shading mode, the metrics and error images, the PNGs; the measured materials' pass. */
#define _XOPEN_SOURCE 700
#include "render_internal.h"
#include "render_pictures.h"
#include "errmsg.h"
#include "draw.h"
#include "exitcodes.h"
#include "outdir.h"
#include "raster.h"
#include "render_report.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------ files */

/* A model label as a file name: "fq:Q=0.64" -> "fq_Q=0.64". */
void label_to_file(const char *label, char *out, size_t len)
{
    size_t i = 0;
    for (; label[i] && i + 1 < len; i++) {
        char c = label[i];
        out[i] = (c == ':' || c == ',' || c == '/' || c == ' ') ? '_' : c;
    }
    out[i] = '\0';
}

void render_rgba_to_rgb(const unsigned *rgba, size_t n, unsigned char *rgb)
{
    for (size_t i = 0; i < n; i++) {
        rgb[3 * i + 0] = (unsigned char)(rgba[i] & 255u);
        rgb[3 * i + 1] = (unsigned char)((rgba[i] >> 8) & 255u);
        rgb[3 * i + 2] = (unsigned char)((rgba[i] >> 16) & 255u);
    }
}

/* ------------------------------------------------------------------ the run */

struct shaded_cache {
    int n;
    struct {
        int mode;
        char label[MODEL_LABEL_MAX];
        unsigned *rgba;
        float *spec;
    } e[2 * RENDER_MAX_MODELS];
};

static void cache_free(struct shaded_cache *c)
{
    for (int i = 0; i < c->n; i++) {
        free(c->e[i].rgba);
        free(c->e[i].spec);
    }
    c->n = 0;
}

/* The end of a pass over a scene: its device buffers (each may be NULL) and its G-buffer. */
void pass_release(cl_mem out_spec, cl_mem out_rgba, cl_mem gbuf, struct gbuffer *g)
{
    if (out_spec)
        clReleaseMemObject(out_spec);
    if (out_rgba)
        clReleaseMemObject(out_rgba);
    if (gbuf)
        clReleaseMemObject(gbuf);
    gbuffer_free(g);
}

/* A pass's device buffers: the G-buffer (copied from g, with gbuf_flags) and the two outputs.
 * `which` ("" or "He ") starts the names in an OpenCL error's message. What was made before a
 * failure is left in the pointers for pass_release. */
int pass_buffers(struct cl_session *s, const struct gbuffer *g, cl_mem_flags gbuf_flags, const char *which,
                 cl_mem *gbuf, cl_mem *out_rgba, cl_mem *out_spec)
{
    int rc = 0;
    cl_int e;
    char what[64];
    *gbuf = clCreateBuffer(s->ctx, gbuf_flags | CL_MEM_COPY_HOST_PTR, g->stride * GB_NPLANES * sizeof(float),
                           g->data, &e);
    snprintf(what, sizeof what, "clCreateBuffer(%sG-buffer)", which);
    CL_CHECK_ERR_GOTO(e, what, done);
    *out_rgba = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, g->stride * sizeof(cl_uint), NULL, &e);
    snprintf(what, sizeof what, "clCreateBuffer(%srgba)", which);
    CL_CHECK_ERR_GOTO(e, what, done);
    *out_spec = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, g->stride * sizeof(cl_float), NULL, &e);
    snprintf(what, sizeof what, "clCreateBuffer(%sspec)", which);
    CL_CHECK_ERR_GOTO(e, what, done);
done:
    return rc;
}

/* Image pass of one scene: every model and its reference shaded at o->width x o->height. */
int image_pass(struct render_device *dev, const struct scene_data *sd,
               const struct render_options *o, const char *stage_dir,
               struct scene_result *res, char *err, size_t errlen)
{
    struct cl_session *s = dev->s;
    const int w = o->width, h = o->height;
    struct gbuffer g;
    struct shaded_cache cache = {0};
    cl_mem gbuf = NULL, out_rgba = NULL, out_spec = NULL;
    unsigned *rgba_m = NULL;
    float *spec_m = NULL, *errimg = NULL, *signed_m = NULL, *grid_err = NULL;
    unsigned char *rgb_m = NULL, *rgb_r = NULL, *grid_m = NULL, *grid_r = NULL;
    int rc = 0;
    double t0 = wall_seconds();
    rc = scene_gbuffer(sd, o, w, h, &g, &res->light, err, errlen);
    if (rc)
        return rc;
    res->raster_seconds = wall_seconds() - t0;
    res->foreground = g.foreground;
    const size_t npix = g.npix;
    if ((rc = pass_buffers(s, &g, CL_MEM_READ_ONLY, "", &gbuf, &out_rgba, &out_spec)))
        goto fail;
    rgba_m = malloc(npix * sizeof *rgba_m);
    spec_m = malloc(npix * sizeof *spec_m);
    errimg = malloc(npix * sizeof *errimg);
    signed_m = malloc(npix * sizeof *signed_m);
    rgb_m = malloc(npix * 3);
    rgb_r = malloc(npix * 3);
    if (!rgba_m || !spec_m || !errimg || !signed_m || !rgb_m || !rgb_r)
        goto oom;
    if (sd->kind == RENDER_SPHERES) {
        grid_err = malloc(npix * sizeof *grid_err);
        grid_m = malloc(npix * 3);
        grid_r = malloc(npix * 3);
        if (!grid_err || !grid_m || !grid_r)
            goto oom;
    }
    char scene_dir[4200];
    path_join(scene_dir, sizeof scene_dir, stage_dir, render_scene_names[sd->kind]);
    if (o->write_images && outdir_prepare(scene_dir, NULL, err, errlen) != 0) {
        rc = EXIT_RUNTIME;
        goto done;
    }

    for (int mi = 0; mi < o->nmodels; mi++) {
        const struct model_spec *m = &o->models[mi];
        struct model_result *mr = &res->models[mi];
        mr->mode = render_shading_mode(m);
        model_reference_spec(m, &mr->ref);
        rc = render_device_shade(dev, gbuf, g.stride, npix, out_rgba, out_spec, m, mr->mode,
                                 &res->light, o, rgba_m, spec_m, NULL);
        if (rc)
            goto fail;
        /* the reference in the model's own shading mode, shaded once per scene */
        int ci = -1, ref_mode = render_reference_mode(mr->mode, &mr->ref);
        for (int k = 0; k < cache.n; k++)
            if (cache.e[k].mode == ref_mode && strcmp(cache.e[k].label, mr->ref.label) == 0)
                ci = k;
        if (ci < 0) {
            ci = cache.n;
            cache.e[ci].mode = ref_mode;
            snprintf(cache.e[ci].label, sizeof cache.e[ci].label, "%s", mr->ref.label);
            cache.e[ci].rgba = malloc(npix * sizeof(unsigned));
            cache.e[ci].spec = malloc(npix * sizeof(float));
            cache.n++;
            if (!cache.e[ci].rgba || !cache.e[ci].spec)
                goto oom;
            rc = render_device_shade(dev, gbuf, g.stride, npix, out_rgba, out_spec, &mr->ref,
                                     ref_mode, &res->light, o, cache.e[ci].rgba,
                                     cache.e[ci].spec, NULL);
            if (rc)
                goto fail;
        }
        const unsigned *rgba_r = cache.e[ci].rgba;
        const float *spec_r = cache.e[ci].spec;
        model_region(sd, o, h, mi, &mr->y0, &mr->y1);
        const int y0 = mr->y0, y1 = mr->y1;
        compute_metrics(&g, y0, y1, rgba_m, spec_m, rgba_r, spec_r, o->threshold, errimg, signed_m,
                        &mr->metrics);
        check_reference(&g, y0, y1, m, mr->mode, &res->light, o, rgba_m, spec_m, &mr->check);
        size_t off = (size_t)y0 * w, n = (size_t)(y1 - y0) * w;
        render_rgba_to_rgb(rgba_m + off, n, rgb_m);
        render_rgba_to_rgb(rgba_r + off, n, rgb_r);
        if (grid_m) {
            memcpy(grid_m + 3 * off, rgb_m, 3 * n);
            memcpy(grid_r + 3 * off, rgb_r, 3 * n);
            /* rows differ in scale (normalised lobes peak near (n+2)/(2 pi)): the grid shows
               each row's error relative to its reference's peak */
            double peak = mr->metrics.peak_reference;
            for (size_t k = 0; k < n; k++)
                grid_err[off + k] = peak > 0 ? (float)(errimg[k] / peak) : errimg[k];
        }
        if (o->write_images) {
            char base[MODEL_LABEL_MAX + 8], title[400], ctitle[400], stitle[400];
            label_to_file(m->label, base, sizeof base);
            const char *sc = render_scene_names[sd->kind];
            snprintf(title, sizeof title,
                     "%s: |%s - %s| specular radiance (%s), max %.3g mean %.3g", sc, m->label,
                     mr->ref.label, render_mode_names[mr->mode], mr->metrics.max_abs,
                     mr->metrics.mean_abs);
            snprintf(ctitle, sizeof ctitle, "%s: reference %s | model %s | error (max %.3g)", sc,
                     mr->ref.label, m->label, mr->metrics.max_abs);
            render_signed_title(stitle, sizeof stitle, sc, m->label, mr->ref.label, mr->metrics.max_abs);
            struct render_picture_set ps = {scene_dir, sc, "", base, w, y1 - y0, rgb_m, rgb_r, errimg,
                                            signed_m, mr->metrics.max_abs, title, stitle, ctitle, mr->image,
                                            mr->error, mr->signed_error, mr->contact};
            if (render_write_pictures(&ps, err, errlen) != 0)
                goto io_fail;
        }
        if (o->verbose)
            render_print_model(sd->kind, m->label, mr);
    }
    if (grid_m && o->write_images) {
        /* the whole grid: row r holds model r, its reference and its error */
        double vmax = 0;
        for (int mi = 0; mi < o->nmodels; mi++) {
            const struct image_metrics *mt = &res->models[mi].metrics;
            if (mt->peak_reference > 0)
                vmax = fmax(vmax, mt->max_abs / mt->peak_reference);
        }
        if (render_write_grid(scene_dir, o, w, h, grid_r, grid_m, grid_err, vmax, err, errlen) != 0)
            goto io_fail;
        snprintf(res->grid_contact, sizeof res->grid_contact, "render/spheres/contact.png");
    }
    goto done;
oom:
    set_err(err, errlen, "%s: out of memory for %dx%d images", render_scene_names[sd->kind], w, h);
    rc = EXIT_RUNTIME;
    goto done;
io_fail:
    rc = EXIT_RUNTIME;
    goto done;
fail:
    if (!err[0])
        set_err(err, errlen, "%s: OpenCL error in the image pass (see above)",
                render_scene_names[sd->kind]);
    rc = rc ? rc : EXIT_RUNTIME;
done:
    cache_free(&cache);
    free(rgba_m);
    free(spec_m);
    free(errimg);
    free(signed_m);
    free(rgb_m);
    free(rgb_r);
    free(grid_err);
    free(grid_m);
    free(grid_r);
    pass_release(out_spec, out_rgba, gbuf, &g);
    return rc;
}

/* A mesh shaded with each measured material beside its fitted lobes (render_measured.c). */
int measured_scene(struct render_device *dev, const struct scene_data *sd, const struct render_options *o,
                   const char *stage_dir, struct scene_result *res, char *err, size_t errlen)
{
    struct gbuffer g;
    struct render_light lt;
    char scene_dir[4200];
    path_join(scene_dir, sizeof scene_dir, stage_dir, render_scene_names[sd->kind]);
    int rc = scene_gbuffer(sd, o, o->width, o->height, &g, &lt, err, errlen);
    if (rc)
        return rc;
    for (int k = 0; rc == 0 && k < o->nmeasured && k < RENDER_MAX_MEASURED; ++k) {
        rc = render_measured_pass(dev, &g, &lt, o, o->measured[k], scene_dir, &res->measured[k], err, errlen);
        res->nmeasured = k + 1;
        if (rc == 0 && o->verbose)
            render_print_measured(sd->kind, &res->measured[k]);
    }
    gbuffer_free(&g);
    return rc;
}
