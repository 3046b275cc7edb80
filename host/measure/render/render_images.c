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

int pixel_buffers_alloc(const struct pixel_buffers *b, size_t npix)
{
    int failed = 0;
    for (int i = 0; i < PIXEL_BUFFERS_MAX; ++i) {
        if (b->rgba[i] && !(*b->rgba[i] = malloc(npix * sizeof **b->rgba[i])))
            failed = 1;
        if (b->floats[i] && !(*b->floats[i] = malloc(npix * sizeof **b->floats[i])))
            failed = 1;
        if (b->doubles[i] && !(*b->doubles[i] = malloc(npix * sizeof **b->doubles[i])))
            failed = 1;
        if (b->rgb[i] && !(*b->rgb[i] = malloc(npix * 3)))
            failed = 1;
    }
    return failed ? -1 : 0;
}

void pixel_buffers_free(const struct pixel_buffers *b)
{
    for (int i = 0; i < PIXEL_BUFFERS_MAX; ++i) {
        if (b->rgba[i])
            free(*b->rgba[i]);
        if (b->floats[i])
            free(*b->floats[i]);
        if (b->doubles[i])
            free(*b->doubles[i]);
        if (b->rgb[i])
            free(*b->rgb[i]);
    }
}

/* The host images of the image pass: the model's shading, its error images and 8-bit colours,
   and on the sphere grid the whole grid's colours and relative errors. */
struct pass_images {
    unsigned *rgba_m;
    float *spec_m, *errimg, *signed_m, *grid_err;
    unsigned char *rgb_m, *rgb_r, *grid_m, *grid_r;
};

/* The pass's images, and apart the sphere grid's. */
static void pass_image_lists(struct pass_images *im, struct pixel_buffers *pass, struct pixel_buffers *grid)
{
    *pass = (struct pixel_buffers){ .rgba = { &im->rgba_m }, .floats = { &im->spec_m, &im->errimg, &im->signed_m },
                                    .rgb = { &im->rgb_m, &im->rgb_r } };
    *grid = (struct pixel_buffers){ .floats = { &im->grid_err }, .rgb = { &im->grid_m, &im->grid_r } };
}

/* Allocates the pass's images for npix pixels (the grid's only when `grid`); -1 when out of
   memory (what was allocated is freed by pass_images_free). */
static int pass_images_alloc(struct pass_images *im, size_t npix, int grid)
{
    struct pixel_buffers pass, grid_images;
    pass_image_lists(im, &pass, &grid_images);
    if (pixel_buffers_alloc(&pass, npix))
        return -1;
    return grid ? pixel_buffers_alloc(&grid_images, npix) : 0;
}

static void pass_images_free(struct pass_images *im)
{
    struct pixel_buffers pass, grid_images;
    pass_image_lists(im, &pass, &grid_images);
    pixel_buffers_free(&pass);
    pixel_buffers_free(&grid_images);
}

/* The reference of a model in its own shading mode, shaded once per scene: its index in the
   cache in *ci. Returns 0, -1 when out of memory, or the shading's failure. */
static int cached_reference(struct render_device *dev, cl_mem gbuf, const struct gbuffer *g, cl_mem out_rgba,
                            cl_mem out_spec, const struct model_result *mr, const struct render_light *lt,
                            const struct render_options *o, struct shaded_cache *cache, int *ci)
{
    int ref_mode = render_reference_mode(mr->mode, &mr->ref);
    *ci = -1;
    for (int k = 0; k < cache->n; k++)
        if (cache->e[k].mode == ref_mode && strcmp(cache->e[k].label, mr->ref.label) == 0)
            *ci = k;
    if (*ci >= 0)
        return 0;
    int i = *ci = cache->n;
    cache->e[i].mode = ref_mode;
    snprintf(cache->e[i].label, sizeof cache->e[i].label, "%s", mr->ref.label);
    cache->e[i].rgba = malloc(g->npix * sizeof(unsigned));
    cache->e[i].spec = malloc(g->npix * sizeof(float));
    cache->n++;
    if (!cache->e[i].rgba || !cache->e[i].spec)
        return -1;
    return render_device_shade(dev, gbuf, g->stride, g->npix, out_rgba, out_spec, &mr->ref, ref_mode, lt, o,
                               cache->e[i].rgba, cache->e[i].spec, NULL);
}

/* A model's rows in the sphere grid: its colours, its reference's and its error relative to
   the reference's peak (rows differ in scale: normalised lobes peak near (n+2)/(2 pi)). */
static void grid_add_rows(struct pass_images *im, size_t off, size_t n, double peak)
{
    memcpy(im->grid_m + 3 * off, im->rgb_m, 3 * n);
    memcpy(im->grid_r + 3 * off, im->rgb_r, 3 * n);
    for (size_t k = 0; k < n; k++)
        im->grid_err[off + k] = peak > 0 ? (float)(im->errimg[k] / peak) : im->errimg[k];
}

/* A model's pictures of a scene: image, error images and contact sheet, rows y0..y1. */
static int model_pictures(const char *scene_dir, int scene, const struct model_spec *m, struct model_result *mr,
                          int w, const struct pass_images *im, char *err, size_t errlen)
{
    char base[MODEL_LABEL_MAX + 8], title[400], ctitle[400], stitle[400];
    label_to_file(m->label, base, sizeof base);
    const char *sc = render_scene_names[scene];
    snprintf(title, sizeof title,
             "%s: |%s - %s| specular radiance (%s), max %.3g (%.3g of the reference's peak) mean %.3g", sc,
             m->label, mr->ref.label, render_mode_names[mr->mode], mr->metrics.max_abs,
             render_max_of_peak(&mr->metrics), mr->metrics.mean_abs);
    snprintf(ctitle, sizeof ctitle, "%s: reference %s | model %s | error, scale 0..max |err| %.3g radiance (%.3g of "
             "the reference's peak)", sc, mr->ref.label, m->label, mr->metrics.max_abs, render_max_of_peak(&mr->metrics));
    snprintf(mr->contact_caption, sizeof mr->contact_caption, "%s", ctitle);
    render_signed_title(stitle, sizeof stitle, sc, m->label, mr->ref.label, mr->metrics.max_abs);
    struct render_picture_set ps = {scene_dir, sc, "", base, w, mr->y1 - mr->y0, im->rgb_m, im->rgb_r, im->errimg,
                                    im->signed_m, mr->metrics.max_abs, title, stitle, ctitle, mr->image,
                                    mr->error, mr->signed_error, mr->contact};
    return render_write_pictures(&ps, err, errlen);
}

/* The whole sphere grid: row r holds model r, its reference and its error. */
static int write_sphere_grid(const char *scene_dir, const struct render_options *o, int w, int h,
                             const struct pass_images *im, struct scene_result *res, char *err, size_t errlen)
{
    double vmax = 0;
    for (int mi = 0; mi < o->nmodels; mi++) {
        const struct image_metrics *mt = &res->models[mi].metrics;
        if (mt->peak_reference > 0)
            vmax = fmax(vmax, mt->max_abs / mt->peak_reference);
    }
    res->grid_max_of_peak = vmax;
    if (render_write_grid(scene_dir, o, w, h, im->grid_r, im->grid_m, im->grid_err, vmax, res->grid_caption,
                          sizeof res->grid_caption, err, errlen) != 0)
        return -1;
    snprintf(res->grid_contact, sizeof res->grid_contact, "render/spheres/contact.png");
    return 0;
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
    struct pass_images im = {0};
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
    if (pass_images_alloc(&im, npix, sd->kind == RENDER_SPHERES) != 0)
        goto oom;
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
                                 &res->light, o, im.rgba_m, im.spec_m, NULL);
        if (rc)
            goto fail;
        int ci;
        rc = cached_reference(dev, gbuf, &g, out_rgba, out_spec, mr, &res->light, o, &cache, &ci);
        if (rc < 0)
            goto oom;
        if (rc)
            goto fail;
        const unsigned *rgba_r = cache.e[ci].rgba;
        const float *spec_r = cache.e[ci].spec;
        model_region(sd, o, h, mi, &mr->y0, &mr->y1);
        const int y0 = mr->y0, y1 = mr->y1;
        compute_metrics(&g, y0, y1, im.rgba_m, im.spec_m, rgba_r, spec_r, o->threshold, im.errimg, im.signed_m,
                        &mr->metrics);
        check_reference(&g, y0, y1, m, mr->mode, &res->light, o, im.rgba_m, im.spec_m, &mr->check);
        render_worst_pixel(&g, &res->light, &mr->metrics, im.spec_m, spec_r, &mr->worst);
        size_t off = (size_t)y0 * w, n = (size_t)(y1 - y0) * w;
        render_rgba_to_rgb(im.rgba_m + off, n, im.rgb_m);
        render_rgba_to_rgb(rgba_r + off, n, im.rgb_r);
        if (im.grid_m)
            grid_add_rows(&im, off, n, mr->metrics.peak_reference);
        if (o->write_images && model_pictures(scene_dir, sd->kind, m, mr, w, &im, err, errlen) != 0)
            goto io_fail;
        if (!o->io.quiet)
            render_print_model(sd->kind, m->label, mr);
    }
    if (im.grid_m && o->write_images && write_sphere_grid(scene_dir, o, w, h, &im, res, err, errlen) != 0)
        goto io_fail;
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
    pass_images_free(&im);
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
        if (rc == 0 && !o->io.quiet)
            render_print_measured(sd->kind, &res->measured[k]);
    }
    gbuffer_free(&g);
    return rc;
}
