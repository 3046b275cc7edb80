/* render.c - the full-image shading passes (see render.h): scenes, G-buffers, the shading
 * kernel per model and its reference, error images and metrics, the double host reference
 * on a sample, timings against the copy kernel, render.json and the PNGs. */
#define _XOPEN_SOURCE 700
#include "render.h"
#include "errmsg.h"

#include "context.h"
#include "draw.h"
#include "exitcodes.h"
#include "geometry.h"
#include "jsonw.h"
#include "outdir.h"
#include "programs.h"
#include "raster.h"
#include "refine.h"
#include "render_pictures.h"
#include "render_report.h"
#include "report.h"
#include "runner.h"

#include <errno.h>
#include <ftw.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The model header as the host's double-precision code (for alpha(n) of the microfacet
   models); the formulas themselves are evaluated through model_eval_host. */
#define REAL double
#define RSCALAR double
#include "brdf_models.h"
#undef REAL
#undef RSCALAR

/* World direction towards the light (upper left, in front), for every scene. */
static const double light_dir_world[3] = {-0.45, 0.6, 0.66};
/* Where the mesh cameras look from (right, above, in front), and their field of view. */
static const double mesh_view_from[3] = {0.35, 0.45, 1.0};
static const double world_up[3] = {0.0, 1.0, 0.0};
#define MESH_FOV_DEG 30.0
#define MESH_FILL 0.92

const char *const render_scene_names[RENDER_SCENE_COUNT] = {"spheres", "teapot", "bunny"};
const char *const render_mode_names[RENDER_MODE_COUNT] = {"lobe-psi", "lobe-theta_h", "cook-torrance-beckmann",
                                                          "cook-torrance-ggx", "physical", "full-brdf",
                                                          "measured"};

/* ------------------------------------------------------------------ options */

void render_options_default(struct render_options *o)
{
    memset(o, 0, sizeof *o);
    for (int i = 0; i < RENDER_SCENE_COUNT; i++)
        o->scene_on[i] = 1;
    o->width = 1920;
    o->height = 1080;
    o->ntime_sizes = 2;
    o->time_w[0] = 1920;
    o->time_h[0] = 1080;
    o->time_w[1] = 3840;
    o->time_h[1] = 2160;
    o->reps = 7;
    o->warmup = 2;
    o->nmodels = model_spec_list_default(o->models, RENDER_MAX_MODELS);
    for (int i = 0; i < models_count() && o->nmodels < RENDER_MAX_MODELS; i++)
        if (models_at(i)->family == MODEL_FAMILY_PHYSICAL)
            model_spec_default(models_at(i), &o->models[o->nmodels++]);
    o->he_material = 0;
    static const double cols[] = {4, 16, 64, 256, 1000};
    o->ncols = 5;
    memcpy(o->sphere_n, cols, sizeof cols);
    o->mesh_n = 64;
    o->tess = 16;
    o->point_light = 0;
    o->exposure = 1.2;
    o->kd = 0.35;
    o->ks = 1.0;
    o->ambient = 0.03;
    o->f0 = 0.5;
    o->tint[0] = 1.0; /* copper-like: the highlight of a lobe with peak 1 stays unsaturated */
    o->tint[1] = 0.72;
    o->tint[2] = 0.45;
    o->threshold = 0.01;
    o->ref_samples = 4096;
    o->teapot_path = RENDER_TEAPOT_PATH;
    o->bunny_path = RENDER_BUNNY_PATH;
    o->write_images = 1;
    o->verbose = 1;
}

int render_check_size(const struct cl_session *s, const char *what, long width, long height,
                      int nmodels_rows, char *err, size_t errlen)
{
    double global_mib = s ? (double)s->global_mem / 1048576.0 : 0;
    double alloc_mib = s ? (double)s->max_alloc / 1048576.0 : 0;
    int ok = width >= RENDER_MIN_SIDE && height >= RENDER_MIN_SIDE && width <= RENDER_MAX_SIDE &&
             height <= RENDER_MAX_SIDE;
    size_t gbytes = ok ? gbuffer_bytes(width, height) : 0;
    if (ok && gbytes == 0)
        ok = 0;
    if (ok && s) {
        /* the G-buffer plus RGBA8 and float outputs on the device; half of global memory
           leaves room for the host's copies (PoCL's device memory is the host's) */
        double dev = (double)gbytes * RENDER_DEVICE_BYTES_PER_PIXEL / (GB_NPLANES * 4.0);
        if (dev > 0.5 * (double)s->global_mem || (double)gbytes > (double)s->max_alloc)
            ok = 0;
    }
    if (!ok) {
        if (s)
            set_err(err, errlen,
                    "%s: %ldx%ld is outside the accepted range: W and H integers in [%d, %d], "
                    "W*H*%d bytes within half the device's global memory (%.0f MiB) and the "
                    "G-buffer (W*H*28 bytes) within its largest buffer (%.0f MiB)",
                    what, width, height, RENDER_MIN_SIDE, RENDER_MAX_SIDE,
                    RENDER_DEVICE_BYTES_PER_PIXEL, 0.5 * global_mib, alloc_mib);
        else
            set_err(err, errlen, "%s: %ldx%ld is outside the accepted range: W and H integers "
                    "in [%d, %d]", what, width, height, RENDER_MIN_SIDE, RENDER_MAX_SIDE);
        return EXIT_USAGE;
    }
    if (nmodels_rows > 0 && height < 8L * nmodels_rows) {
        set_err(err, errlen,
                "%s: %ldx%ld is too low for the sphere grid: it needs at least 8 pixel rows per "
                "model (H >= %d for %d models)",
                what, width, height, 8 * nmodels_rows, nmodels_rows);
        return EXIT_USAGE;
    }
    return 0;
}

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

int render_device_open(struct render_device *d, struct cl_session *s,
                       const struct render_options *o, char *err, size_t errlen)
{
    int rc = 0;
    cl_int e;
    memset(d, 0, sizeof *d);
    d->s = s;
    d->global_size = RENDER_WORK_ITEMS;
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
    size_t global = d->global_size, local = 1;
    CL_CHECK_GOTO(clEnqueueNDRangeKernel(d->s->queue, k, 1, NULL, &global, &local, 0, NULL, &ev),
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
    memset(p, 0, sizeof *p);
    p->s[0] = (float)lt->eye[0];
    p->s[1] = (float)lt->eye[1];
    p->s[2] = (float)lt->eye[2];
    p->s[3] = (float)o->ambient;
    p->s[4] = (float)lt->light[0];
    p->s[5] = (float)lt->light[1];
    p->s[6] = (float)lt->light[2];
    p->s[7] = lt->point ? 1.0f : 0.0f;
    p->s[8] = (float)lt->intensity;
    p->s[9] = (float)o->kd;
    p->s[10] = (float)o->ks;
    p->s[11] = (float)o->f0;
}

static int set_common_args(cl_kernel k, cl_mem gbuf, size_t stride, size_t npix, cl_mem rgba,
                           cl_mem spec)
{
    int rc = 0;
    cl_uint st = (cl_uint)stride, nch = (cl_uint)((npix + 15) / 16);
    CL_CHECK_GOTO(clSetKernelArg(k, 0, sizeof gbuf, &gbuf), done);
    CL_CHECK_GOTO(clSetKernelArg(k, 1, sizeof st, &st), done);
    CL_CHECK_GOTO(clSetKernelArg(k, 2, sizeof nch, &nch), done);
    CL_CHECK_GOTO(clSetKernelArg(k, 3, sizeof rgba, &rgba), done);
    CL_CHECK_GOTO(clSetKernelArg(k, 4, sizeof spec, &spec), done);
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
    CL_CHECK_GOTO(clSetKernelArg(shade, 5, sizeof kmode, &kmode), done);
    CL_CHECK_GOTO(clSetKernelArg(shade, 6, sizeof kmodel, &kmodel), done);
    CL_CHECK_GOTO(clSetKernelArg(shade, 7, sizeof p0, &p0), done);
    CL_CHECK_GOTO(clSetKernelArg(shade, 8, sizeof p1, &p1), done);
    CL_CHECK_GOTO(clSetKernelArg(shade, 9, sizeof params, &params), done);
    CL_CHECK_GOTO(clSetKernelArg(shade, 10, sizeof d->display_table, &d->display_table),
                  done);
    cl_mem merl = d->merl_table ? d->merl_table : d->no_table;
    CL_CHECK_GOTO(clSetKernelArg(shade, 11, sizeof merl, &merl), done);
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

static int device_copy(struct render_device *d, cl_mem gbuf, size_t stride, size_t npix,
                       cl_mem out_rgba, cl_mem out_spec, double *seconds)
{
    int rc = set_common_args(d->copy, gbuf, stride, npix, out_rgba, out_spec);
    if (rc)
        return rc;
    return launch(d, d->copy, NULL, seconds);
}

/* ------------------------------------------------------------------ scenes */

struct scene_data {
    int kind;
    struct mesh mesh;          /* teapot and bunny */
    size_t patches;            /* teapot: Bezier patches read */
    char source[600];          /* the file read, or "analytic" */
};

static int scene_load(int kind, const struct render_options *o, struct scene_data *sd, char *err,
                      size_t errlen)
{
    memset(sd, 0, sizeof *sd);
    sd->kind = kind;
    if (kind == RENDER_SPHERES) {
        snprintf(sd->source, sizeof sd->source, "analytic spheres");
        return 0;
    }
    const char *path = kind == RENDER_TEAPOT ? o->teapot_path : o->bunny_path;
    const char *def = kind == RENDER_TEAPOT ? RENDER_TEAPOT_PATH : RENDER_BUNNY_PATH;
    const char *pkg = kind == RENDER_TEAPOT ? RENDER_TEAPOT_PACKAGE : RENDER_BUNNY_PACKAGE;
    snprintf(sd->source, sizeof sd->source, "%s", path);
    if (access(path, R_OK) != 0) {
        int is_default = strcmp(path, def) == 0;
        if (is_default)
            set_err(err, errlen,
                    "%s scene: %s is missing: it comes with Debian's %s package (apt-get install "
                    "%s; where an image excludes /usr/share/doc from installs, take the file out "
                    "of the package: apt-get download %s && dpkg-deb -x %s_*.deb DIR; "
                    "scripts/setup.sh does both)",
                    render_scene_names[kind], path, pkg, pkg, pkg, pkg);
        else
            set_err(err, errlen, "%s scene: cannot read %s: %s", render_scene_names[kind], path,
                    strerror(errno));
        return is_default ? EXIT_RUNTIME : EXIT_USAGE;
    }
    int rc;
    if (kind == RENDER_TEAPOT) {
        struct bezier_patch *p = NULL;
        rc = patches_read(path, &p, &sd->patches, err, errlen);
        if (rc == 0)
            rc = patches_tessellate(p, sd->patches, o->tess, &sd->mesh, err, errlen);
        free(p);
        if (rc == 0) {
            /* the file's teapot stands on z = 0 with z up; the scenes are y-up: a rotation
               of -90 degrees about x, (x, y, z) -> (x, z, -y) */
            for (size_t v = 0; v < sd->mesh.nverts; v++) {
                float *q = sd->mesh.pos + 3 * v, *n = sd->mesh.nrm + 3 * v, t;
                t = q[1];
                q[1] = q[2];
                q[2] = -t;
                t = n[1];
                n[1] = n[2];
                n[2] = -t;
            }
        }
    } else {
        rc = obj_read(path, &sd->mesh, err, errlen);
        if (rc == 0)
            rc = mesh_smooth_normals(&sd->mesh, err, errlen);
    }
    if (rc)
        mesh_free(&sd->mesh);
    return rc;
}

/* G-buffer and light of a scene at a size. */
static int scene_gbuffer(const struct scene_data *sd, const struct render_options *o, int w, int h,
                         struct gbuffer *g, struct render_light *lt, char *err, size_t errlen)
{
    int rc = gbuffer_alloc(g, w, h, err, errlen);
    if (rc)
        return rc;
    struct camera cam;
    if (sd->kind == RENDER_SPHERES) {
        rc = raster_spheres(g, o->nmodels, o->ncols, o->sphere_n, &cam, err, errlen);
    } else {
        camera_fit_mesh(&cam, &sd->mesh, mesh_view_from, world_up, MESH_FOV_DEG,
                        (double)w / h, MESH_FILL);
        rc = raster_mesh(g, &sd->mesh, &cam, (float)o->mesh_n, err, errlen);
    }
    if (rc) {
        gbuffer_free(g);
        return rc;
    }
    double dir[3] = {light_dir_world[0], light_dir_world[1], light_dir_world[2]};
    vec3_normalize(dir);
    double d[3] = {cam.eye[0] - cam.target[0], cam.eye[1] - cam.target[1],
                   cam.eye[2] - cam.target[2]};
    double dist = sqrt(vec3_dot(d, d));
    for (int c = 0; c < 3; c++)
        lt->eye[c] = cam.eye[c];
    lt->point = o->point_light;
    if (o->point_light) {
        /* at the camera's distance from the scene's centre, E = 1 at the centre */
        for (int c = 0; c < 3; c++)
            lt->light[c] = cam.target[c] + dist * dir[c];
        lt->intensity = dist * dist;
    } else {
        for (int c = 0; c < 3; c++)
            lt->light[c] = dir[c];
        lt->intensity = 1.0;
    }
    return 0;
}

/* Rows [y0, y1) of the frame a model's figures cover: its band of the sphere grid (the rows
   raster_spheres gives to grid row `row`), or the whole frame. */
static void model_region(const struct scene_data *sd, const struct render_options *o, int h,
                         int row, int *y0, int *y1)
{
    if (sd->kind != RENDER_SPHERES) {
        *y0 = 0;
        *y1 = h;
        return;
    }
    int a = -1, b = h;
    for (int y = 0; y < h; y++) {
        int r = (int)((long)y * o->nmodels / h);
        if (r == row && a < 0)
            a = y;
        if (r > row) {
            b = y;
            break;
        }
    }
    *y0 = a < 0 ? 0 : a;
    *y1 = b;
}

/* ------------------------------------------------------------------ metrics */

/* Error, metrics and the error pictures for rows [y0, y1). errimg: (y1-y0) x w floats of
   |model - reference|; signed_img (NULL: none) the same of model - reference. */
static void compute_metrics(const struct gbuffer *g, int y0, int y1, const unsigned *rgba_m,
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
static void check_reference(const struct gbuffer *g, int y0, int y1, const struct model_spec *m,
                            int mode, const struct render_light *lt, const struct render_options *o,
                            const unsigned *rgba, const float *spec, struct reference_check *rc)
{
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

/* ------------------------------------------------------------------ files */

/* A model label as a file name: "fq:Q=0.64" -> "fq_Q=0.64". */
static void label_to_file(const char *label, char *out, size_t len)
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

static int remove_entry(const char *path, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb;
    (void)flag;
    (void)ftw;
    return remove(path);
}

static void remove_tree(const char *dir)
{
    nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
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

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The end of a pass over a scene: its device buffers (each may be NULL) and its G-buffer. */
static void pass_release(cl_mem out_spec, cl_mem out_rgba, cl_mem gbuf, struct gbuffer *g)
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
static int pass_buffers(struct cl_session *s, const struct gbuffer *g, cl_mem_flags gbuf_flags, const char *which,
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
static int image_pass(struct render_device *dev, const struct scene_data *sd,
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

/* A mesh shaded by He's model (o->he_material), then by Blinn-Phong at the n (and scale) that
   fits He's specular radiance best, and by each cheap lobe of the run (quadratic and rational
   families) at that n in the Blinn variable; error images against He's. */
static int he_pass(struct render_device *dev, const struct scene_data *sd, const struct render_options *o,
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
    unsigned *rgba_he = NULL, *rgba_b = NULL, *rgba_m = NULL;
    float *spec_he = NULL, *spec_b = NULL, *spec_m = NULL, *errimg = NULL, *signed_img = NULL;
    unsigned char *rgb_he = NULL, *rgb = NULL;
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
    rgba_he = malloc(npix * sizeof *rgba_he);
    rgba_b = malloc(npix * sizeof *rgba_b);
    rgba_m = malloc(npix * sizeof *rgba_m);
    spec_he = malloc(npix * sizeof *spec_he);
    spec_b = malloc(npix * sizeof *spec_b);
    spec_m = malloc(npix * sizeof *spec_m);
    errimg = malloc(npix * sizeof *errimg);
    signed_img = malloc(npix * sizeof *signed_img);
    rgb_he = malloc(npix * 3);
    rgb = malloc(npix * 3);
    fit.a = malloc(npix * sizeof *fit.a);
    fit.c = malloc(npix * sizeof *fit.c);
    fit.h = malloc(npix * sizeof *fit.h);
    if (!rgba_he || !rgba_b || !rgba_m || !spec_he || !spec_b || !spec_m || !errimg || !signed_img || !rgb_he || !rgb || !fit.a ||
        !fit.c || !fit.h) {
        set_err(err, errlen, "%s: out of memory for the He comparison", sc);
        rc = EXIT_RUNTIME;
        goto done;
    }
    if ((rc = render_device_shade(dev, gbuf, g.stride, npix, out_rgba, out_spec, &hc->he, SHADE_PHYSICAL, &lt, o,
                                  rgba_he, spec_he, NULL)) != 0)
        goto fail;
    /* the fit's inputs: every lit foreground pixel, in double from the G-buffer */
    const float *px = gbuffer_plane(&g, GB_PX), *py = gbuffer_plane(&g, GB_PY), *pz = gbuffer_plane(&g, GB_PZ);
    const float *nx = gbuffer_plane(&g, GB_NX), *ny = gbuffer_plane(&g, GB_NY), *nz = gbuffer_plane(&g, GB_NZ);
    float *sh = gbuffer_plane(&g, GB_SHIN);
    struct model_spec blinn;
    model_spec_default(models_find("blinn"), &blinn);
    for (size_t i = 0; i < npix; i++) {
        if (!(sh[i] > 0))
            continue;
        double pos[3] = { px[i], py[i], pz[i] }, nrm[3] = { nx[i], ny[i], nz[i] }, spec1, rad;
        /* Blinn-Phong at n = 1 gives E (N.L) ks c; with it and c the lobe at any n is A c^n */
        render_shade_ref(&blinn, SHADE_LOBE_THETA_H, &lt, o, pos, nrm, 1.0, &spec1, &rad);
        double v[3], l[3], hv[3];
        for (int k = 0; k < 3; k++) {
            v[k] = lt.eye[k] - pos[k];
            l[k] = lt.point ? lt.light[k] - pos[k] : lt.light[k];
        }
        vec3_normalize(v);
        vec3_normalize(l);
        for (int k = 0; k < 3; k++)
            hv[k] = l[k] + v[k];
        vec3_normalize(hv);
        double c = vec3_dot(nrm, hv);
        if (!(spec1 > 0 && c > 0))
            continue;
        fit.a[fit.count] = spec1 / c;
        fit.c[fit.count] = c;
        fit.h[fit.count] = spec_he[i];
        fit.hh += (double)spec_he[i] * spec_he[i];
        fit.count++;
    }
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
    render_rgba_to_rgb(rgba_he, npix, rgb_he);
    if (o->write_images) {
        char base[MODEL_LABEL_MAX + 8], name[300], path[4600];
        label_to_file(hc->he.label, base, sizeof base);
        snprintf(name, sizeof name, "he_%s.png", base);
        snprintf(hc->he_image, sizeof hc->he_image, "render/%s/he_%s.png", sc, base);
        path_join(path, sizeof path, scene_dir, name);
        if (draw_png_rgb8(path, w, h, rgb_he, err, errlen) != 0) {
            rc = EXIT_RUNTIME;
            goto done;
        }
    }
    /* entry 0: Blinn-Phong at the fitted n; then the cheap lobes at that n */
    hc->count = 0;
    for (int mi = -1; mi < o->nmodels && hc->count < RENDER_MAX_MODELS + 1; mi++) {
        const struct model_spec *m = mi < 0 ? &blinn : &o->models[mi];
        if (mi >= 0 && m->info->family != MODEL_FAMILY_QUADRATIC && m->info->family != MODEL_FAMILY_RATIONAL)
            continue;
        struct he_entry *en = &hc->e[hc->count];
        unsigned *rg = mi < 0 ? rgba_b : rgba_m;
        float *sp = mi < 0 ? spec_b : spec_m;
        if ((rc = render_device_shade(dev, gbuf, g.stride, npix, out_rgba, out_spec, m, SHADE_LOBE_THETA_H, &lt, &of,
                                      rg, sp, NULL)) != 0)
            goto fail;
        snprintf(en->label, sizeof en->label, "%s@n=%.4g", m->label, hc->n_fit);
        compute_metrics(&g, 0, h, rg, sp, rgba_he, spec_he, o->threshold, errimg, signed_img, &en->metrics);
        en->max_abs_vs_blinn = 0;
        for (size_t i = 0; i < npix; i++)
            if (sh[i] > 0)
                en->max_abs_vs_blinn = fmax(en->max_abs_vs_blinn, fabs((double)sp[i] - (double)spec_b[i]));
        if (o->write_images) {
            char base[MODEL_LABEL_MAX + 8];
            label_to_file(m->label, base, sizeof base);
            int all_pictures = mi < 0 || m->info->kernel_id == BRDF_FQ2;
            if ((rc = he_pictures(scene_dir, sc, base, w, h, rg, rgb_he, rgb, errimg, signed_img, en, hc->he.label, all_pictures,
                                  err, errlen)) != 0)
                goto done;
        }
        hc->count++;
    }
    hc->done = 1;
    if (o->verbose)
        render_print_he(sd->kind, hc);
    goto done;
fail:
    if (!err[0])
        set_err(err, errlen, "%s: OpenCL error in the He comparison (see above)", sc);
    rc = rc ? rc : EXIT_RUNTIME;
done:
    free(fit.a);
    free(fit.c);
    free(fit.h);
    free(rgba_he);
    free(rgba_b);
    free(rgba_m);
    free(spec_he);
    free(spec_b);
    free(spec_m);
    free(signed_img);
    free(errimg);
    free(rgb_he);
    free(rgb);
    pass_release(out_spec, out_rgba, gbuf, &g);
    return rc;
}

/* A mesh shaded with each measured material beside its fitted lobes (render_measured.c). */
static int measured_scene(struct render_device *dev, const struct scene_data *sd, const struct render_options *o,
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

/* The models and their references, each once per shading mode, in the order timed. */
static void timed_entries(const struct render_options *o, struct size_timing *st)
{
    st->nentries = 0;
    for (int pass = 0; pass < 2; pass++)
        for (int mi = 0; mi < o->nmodels; mi++) {
            struct model_spec ref;
            const struct model_spec *m = &o->models[mi];
            int mode = render_shading_mode(m);
            if (pass == 1) {
                model_reference_spec(m, &ref);
                mode = render_reference_mode(mode, &ref);
            }
            const struct model_spec *sp = pass == 0 ? m : &ref;
            int found = 0;
            for (int k = 0; k < st->nentries; k++)
                if (st->entries[k].mode == mode && strcmp(st->entries[k].spec.label, sp->label) == 0)
                    found = 1;
            if (found)
                continue;
            struct timed_entry *te = &st->entries[st->nentries++];
            memset(te, 0, sizeof *te);
            te->spec = *sp;
            te->mode = mode;
            te->is_model = pass == 0;
            if (mode == render_shading_mode(sp))
                snprintf(te->name, sizeof te->name, "%s", sp->label);
            else
                snprintf(te->name, sizeof te->name, "%s@%s", sp->label, render_mode_names[mode]);
        }
}

/* A pass of the timing as an item of the measurement runner (host/core/runner.h): one launch
   of the shading kernel of an entry (te) over the G-buffer, or of the copy kernel (te NULL). */
struct pass_item {
    struct render_device *dev;
    const struct gbuffer *g;
    cl_mem gbuf, out_rgba, out_spec;
    const struct timed_entry *te;
    const struct render_light *lt;
    const struct render_options *o;
};

static int pass_item_launch(void *ctx, long iters, double *seconds, char *reason, size_t reason_len)
{
    const struct pass_item *p = ctx;
    (void)iters;   /* a pass is the whole image: not calibrated */
    int rc = p->te ? render_device_shade(p->dev, p->gbuf, p->g->stride, p->g->npix, p->out_rgba, p->out_spec,
                                         &p->te->spec, p->te->mode, p->lt, p->o, NULL, NULL, seconds)
                   : device_copy(p->dev, p->gbuf, p->g->stride, p->g->npix, p->out_rgba, p->out_spec, seconds);
    if (rc) {
        snprintf(reason, reason_len, "an OpenCL error in the timing pass (see above)");
        return -1;
    }
    return 0;
}

/* Timing of one scene at one size by the measurement runner: every entry's shading pass an
   item, the copy kernel (the same G-buffer read, the same image written, no shading) the
   reference timed three times a round; o->reps rounds in a fresh random order each, after
   o->warmup warm-up passes of each. */
static int time_pass(struct render_device *dev, const struct scene_data *sd,
                     const struct render_options *o, int w, int h, struct size_timing *st,
                     char *err, size_t errlen)
{
    struct cl_session *s = dev->s;
    struct gbuffer g;
    struct render_light lt;
    cl_mem gbuf = NULL, out_rgba = NULL, out_spec = NULL;
    struct runner_item *items = NULL;
    struct pass_item *pi = NULL;
    struct runner run;
    int ran = 0;
    int rc = scene_gbuffer(sd, o, w, h, &g, &lt, err, errlen);
    if (rc)
        return rc;
    st->w = w;
    st->h = h;
    st->foreground = g.foreground;
    timed_entries(o, st);
    int n = st->nentries + 1;
    items = calloc((size_t)n, sizeof *items);
    pi = calloc((size_t)n, sizeof *pi);
    if (!items || !pi) {
        set_err(err, errlen, "out of memory");
        rc = EXIT_RUNTIME;
        goto done;
    }
    if ((rc = pass_buffers(s, &g, CL_MEM_READ_ONLY, "", &gbuf, &out_rgba, &out_spec)))
        goto fail;
    for (int k = 0; k < n; k++) {
        pi[k] = (struct pass_item){ dev, &g, gbuf, out_rgba, out_spec, k < st->nentries ? &st->entries[k] : NULL,
                                    &lt, o };
        items[k] = (struct runner_item){ .name = k < st->nentries ? st->entries[k].name : "copy",
                                         .launch = pass_item_launch, .ctx = &pi[k], .calibrate = 0, .iters = 1,
                                         .work_per_iter = (double)g.npix,
                                         .cpu_threads = s->is_cpu ? (int)s->compute_units : 0 };
        /* the runner warms each up once; the rest of o->warmup here */
        for (int r = 1; r < o->warmup; r++) {
            double t;
            char why[RUNNER_REASON];
            if (pass_item_launch(&pi[k], 1, &t, why, sizeof why)) {
                rc = EXIT_RUNTIME;
                goto fail;
            }
        }
    }
    runner_init(&run, items, n);
    run.reference = n - 1;
    run.rounds = o->reps;
    if (runner_run(&run)) {
        set_err(err, errlen, "out of memory");
        rc = EXIT_RUNTIME;
        runner_release(&run);
        goto done;
    }
    ran = 1;
    const struct runner_item *copy = &items[n - 1];
    if (!copy->ok) {
        rc = EXIT_RUNTIME;
        goto fail;
    }
    double *cs = malloc((size_t)copy->nreps * sizeof *cs);
    if (!cs) {
        set_err(err, errlen, "out of memory");
        rc = EXIT_RUNTIME;
        goto done;
    }
    memcpy(cs, copy->seconds, (size_t)copy->nreps * sizeof *cs);
    st->copy_med = median(cs, copy->nreps);
    free(cs);
    for (int k = 0; k < st->nentries; k++) {
        struct timed_entry *te = &st->entries[k];
        struct runner_item *it = &items[k];
        if (!it->ok) {
            rc = EXIT_RUNTIME;
            goto fail;
        }
        int reps = it->nreps;
        te->nreps = reps < RENDER_MAX_KEPT_REPS ? reps : RENDER_MAX_KEPT_REPS;
        memcpy(te->rep_s, it->seconds, (size_t)te->nreps * sizeof *it->seconds);   /* before median() sorts */
        te->med = median(it->seconds, reps);
        te->min = it->seconds[0];
        te->max = it->seconds[reps - 1];
        te->copy_med = st->copy_med;
        if (!(te->med > 0) || !(te->copy_med > 0)) {
            set_err(err, errlen, "%s: the profiling timer gave no time for %s", render_scene_names[sd->kind],
                    te->name);
            rc = EXIT_RUNTIME;
            goto done;
        }
    }
    goto done;
fail:
    if (!err[0])
        set_err(err, errlen, "%s: OpenCL error in the timing pass at %dx%d (see above)",
                render_scene_names[sd->kind], w, h);
    rc = rc ? rc : EXIT_RUNTIME;
done:
    if (ran)
        runner_release(&run);
    free(pi);
    free(items);
    pass_release(out_spec, out_rgba, gbuf, &g);
    return rc;
}

int render_run(struct cl_session *s, const struct render_options *o, const char *out_dir,
               char **summary_md, char *err, size_t errlen)
{
    int rc = 0;
    err[0] = '\0';
    if (summary_md)
        *summary_md = NULL;
    if (o->nmodels < 1 || o->nmodels > RENDER_MAX_MODELS || o->ncols < 1 ||
        o->ncols > RENDER_MAX_COLS || o->reps < 1 || o->warmup < 0) {
        set_err(err, errlen, "render: bad options (models 1..%d, sphere columns 1..%d, reps >= 1)",
                RENDER_MAX_MODELS, RENDER_MAX_COLS);
        return EXIT_USAGE;
    }
    int rows = o->scene_on[RENDER_SPHERES] ? o->nmodels : 0;
    if ((rc = render_check_size(s, "--size", o->width, o->height, rows, err, errlen)))
        return rc;
    for (int i = 0; i < o->ntime_sizes; i++)
        if ((rc = render_check_size(s, "--time-sizes", o->time_w[i], o->time_h[i], rows, err,
                                    errlen)))
            return rc;

    struct scene_result *res = calloc(RENDER_SCENE_COUNT, sizeof *res);
    struct render_device dev;
    memset(&dev, 0, sizeof dev);
    char stage[4200] = "", final_dir[4200], old_dir[4200] = "";
    if (!res) {
        set_err(err, errlen, "out of memory");
        return EXIT_RUNTIME;
    }
    /* every scene file is read and checked before anything is rendered or written: a bad
       --teapot-file or --bunny-file is refused at once, not after the scenes before it */
    struct scene_data scenes[RENDER_SCENE_COUNT];
    memset(scenes, 0, sizeof scenes);
    for (int si = 0; si < RENDER_SCENE_COUNT; si++)
        if (o->scene_on[si] && (rc = scene_load(si, o, &scenes[si], err, errlen)))
            goto done;
    if (outdir_prepare(out_dir, NULL, err, errlen) != 0) {
        rc = EXIT_RUNTIME;
        goto done;
    }
    /* everything is staged in a fresh folder and moved into place at the end */
    char name[64];
    snprintf(name, sizeof name, ".render-staging-%ld", (long)getpid());
    path_join(stage, sizeof stage, out_dir, name);
    remove_tree(stage);
    if (outdir_prepare(stage, NULL, err, errlen) != 0) {
        stage[0] = '\0';
        rc = EXIT_RUNTIME;
        goto done;
    }
    if ((rc = render_device_open(&dev, s, o, err, errlen)))
        goto done;

    for (int si = 0; si < RENDER_SCENE_COUNT; si++) {
        if (!o->scene_on[si])
            continue;
        struct scene_result *sr = &res[si];
        struct scene_data sd = scenes[si];
        double t0 = wall_seconds();
        sr->kind = si;
        snprintf(sr->source, sizeof sr->source, "%s", sd.source);
        sr->triangles = sd.mesh.ntris;
        sr->patches = sd.patches;
        if (o->verbose)
            render_print_scene(sr);
        rc = image_pass(&dev, &sd, o, stage, sr, err, errlen);
        if (rc == 0 && o->verbose)
            render_print_check(sr, o->nmodels);
        if (rc == 0 && o->he_material >= 0 && si != RENDER_SPHERES)
            rc = he_pass(&dev, &sd, o, stage, sr, err, errlen);
        if (rc == 0 && o->nmeasured > 0 && si != RENDER_SPHERES)
            rc = measured_scene(&dev, &sd, o, stage, sr, err, errlen);
        for (int ti = 0; rc == 0 && ti < o->ntime_sizes; ti++) {
            rc = time_pass(&dev, &sd, o, o->time_w[ti], o->time_h[ti], &sr->timings[ti], err,
                           errlen);
            sr->ntimings = ti + 1;
        }
        if (rc)
            goto done;
        sr->done = 1;
        if (o->verbose) {
            render_print_timings(sr);
            printf("  (%s: %.1f s)\n", render_scene_names[si], wall_seconds() - t0);
        }
    }

    /* move the staged pictures into place, then write render.json */
    path_join(final_dir, sizeof final_dir, out_dir, "render");
    struct stat st;
    if (stat(final_dir, &st) == 0) {
        snprintf(name, sizeof name, ".render-old-%ld", (long)getpid());
        path_join(old_dir, sizeof old_dir, out_dir, name);
        remove_tree(old_dir);
        if (rename(final_dir, old_dir) != 0) {
            set_err(err, errlen, "cannot move %s aside: %s", final_dir, strerror(errno));
            old_dir[0] = '\0';
            rc = EXIT_RUNTIME;
            goto done;
        }
    }
    if (rename(stage, final_dir) != 0) {
        set_err(err, errlen, "cannot move %s to %s: %s", stage, final_dir, strerror(errno));
        if (old_dir[0])
            rename(old_dir, final_dir);
        old_dir[0] = '\0';
        rc = EXIT_RUNTIME;
        goto done;
    }
    stage[0] = '\0';
    char json_path[4300];
    path_join(json_path, sizeof json_path, out_dir, "render.json");
    if (render_write_json(json_path, s, o, res, dev.display_code_error, err, errlen) != 0) {
        rc = EXIT_RUNTIME;
        goto done;
    }
    if (summary_md)
        *summary_md = render_summary_markdown(o, res, s);
done:
    for (int si = 0; si < RENDER_SCENE_COUNT; si++)
        mesh_free(&scenes[si].mesh);
    if (stage[0])
        remove_tree(stage);
    if (old_dir[0])
        remove_tree(old_dir);
    render_device_close(&dev);
    free(res);
    return rc;
}
