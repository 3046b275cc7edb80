/* render.c - the full-image shading passes (see render.h): the options and their checks, and
 * the run (every scene file read first, the passes staged in a fresh folder moved into place,
 * render.json). The passes are in render_images.c (the shaded models, error images, metrics),
 * render_fit.c (He against the lobes), render_timing.c; the scenes in render_scene.c, the
 * metrics in render_metrics.c, the shading and its host reference in render_shade.c. */
#define _XOPEN_SOURCE 700
#include "render.h"
#include "render_internal.h"
#include "errmsg.h"

#include "context.h"
#include "exitcodes.h"
#include "outdir.h"
#include "render_report.h"

#include <errno.h>
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

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
    }

int render_check_size(const struct cl_session *s, const char *what, long width, long height,
                      int nmodels_rows, char *err, size_t errlen)
{
    double global_mib = s ? (double)s->global_mem / 1048576.0 : 0;
    double alloc_mib = s ? (double)s->max_alloc / 1048576.0 : 0;
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    double phys_mib = pages > 0 && page > 0 ? (double)pages * (double)page / 1048576.0 : 0;
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
        /* the host's own images, and on a CPU device the device's buffers too, in this
           machine's memory: a size past it would end the run by the kernel's OOM killer */
        double host = (double)gbytes * RENDER_HOST_BYTES_PER_PIXEL / (GB_NPLANES * 4.0) + (s->is_cpu ? dev : 0.0);
        if (ok && phys_mib > 0 && host > 0.75 * phys_mib * 1048576.0) {
            set_err(err, errlen,
                    "%s: %ldx%ld is outside the accepted range: W*H*%d bytes of host images%s within "
                    "three quarters of this machine's memory (%.0f MiB)",
                    what, width, height, RENDER_HOST_BYTES_PER_PIXEL,
                    s->is_cpu ? " and the CPU device's buffers" : "", 0.75 * phys_mib);
            return EXIT_USAGE;
        }
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

/* The options and every size against the device's limits. */
static int run_check(struct cl_session *s, const struct render_options *o, char *err, size_t errlen)
{
    int rc;
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
    return 0;
}

/* Makes the staging folder, a fresh one under out_dir (stage receives its path, or "" when it
 * could not be made). */
static int stage_open(const char *out_dir, char *stage, size_t stage_len, char *err, size_t errlen)
{
    stage[0] = '\0';
    /* one run writes a folder at a time (outdir_lock): a second render there is refused */
    if (outdir_prepare(out_dir, NULL, err, errlen) != 0 || outdir_lock(out_dir, "--out", err, errlen) != 0)
        return EXIT_RUNTIME;
    char name[64];
    snprintf(name, sizeof name, ".render-staging-%ld", (long)getpid());
    path_join(stage, stage_len, out_dir, name);
    remove_tree(stage);
    if (outdir_prepare(stage, NULL, err, errlen) != 0) {
        stage[0] = '\0';
        return EXIT_RUNTIME;
    }
    return 0;
}

/* One scene's passes: the images, He against the lobes, the measured materials, the timings. */
static int run_scene(struct render_device *dev, const struct scene_data *scene, const struct render_options *o,
                     const char *stage, struct scene_result *sr, char *err, size_t errlen)
{
    int si = scene->kind;
    struct scene_data sd = *scene;
    double t0 = wall_seconds();
    sr->kind = si;
    snprintf(sr->source, sizeof sr->source, "%s", sd.source);
    sr->triangles = sd.mesh.ntris;
    sr->patches = sd.patches;
    if (!o->io.quiet)
        render_print_scene(sr);
    int rc = image_pass(dev, &sd, o, stage, sr, err, errlen);
    if (rc == 0 && !o->io.quiet)
        render_print_check(sr, o->nmodels);
    if (rc == 0 && o->he_material >= 0 && si != RENDER_SPHERES)
        rc = he_pass(dev, &sd, o, stage, sr, err, errlen);
    if (rc == 0 && o->nmeasured > 0 && si != RENDER_SPHERES)
        rc = measured_scene(dev, &sd, o, stage, sr, err, errlen);
    for (int ti = 0; rc == 0 && ti < o->ntime_sizes; ti++) {
        rc = time_pass(dev, &sd, o, o->time_w[ti], o->time_h[ti], &sr->timings[ti], err,
                       errlen);
        sr->ntimings = ti + 1;
    }
    if (rc)
        return rc;
    sr->done = 1;
    if (!o->io.quiet) {
        render_print_timings(sr);
        printf("  (%s: %.1f s)\n", render_scene_names[si], wall_seconds() - t0);
    }
    return 0;
}

/* Moves the staged pictures into place as out_dir/render, the earlier folder aside into
 * old_dir first (restored when the move fails). stage becomes "" once moved. */
static int stage_commit(const char *out_dir, char *stage, char *old_dir, size_t old_len, char *err, size_t errlen)
{
    char final_dir[4200], name[64];
    path_join(final_dir, sizeof final_dir, out_dir, "render");
    struct stat st;
    if (stat(final_dir, &st) == 0) {
        snprintf(name, sizeof name, ".render-old-%ld", (long)getpid());
        path_join(old_dir, old_len, out_dir, name);
        remove_tree(old_dir);
        if (rename(final_dir, old_dir) != 0) {
            set_err(err, errlen, "cannot move %s aside: %s", final_dir, strerror(errno));
            old_dir[0] = '\0';
            return EXIT_RUNTIME;
        }
    }
    if (rename(stage, final_dir) != 0) {
        set_err(err, errlen, "cannot move %s to %s: %s", stage, final_dir, strerror(errno));
        if (old_dir[0])
            rename(old_dir, final_dir);
        old_dir[0] = '\0';
        return EXIT_RUNTIME;
    }
    stage[0] = '\0';
    return 0;
}

void render_result_free(struct render_result *r)
{
    (void)r;   /* nothing held today: kept so that callers need not change when it holds more */
}

int render_run(struct cl_session *s, const struct render_options *o, struct render_result *r)
{
    const char *out_dir = o->io.out_dir;
    char *err = r->err;
    const size_t errlen = sizeof r->err;
    int rc = 0;
    err[0] = '\0';
    if ((rc = run_check(s, o, err, errlen)))
        return rc;

    struct scene_result *res = calloc(RENDER_SCENE_COUNT, sizeof *res);
    struct render_device dev;
    memset(&dev, 0, sizeof dev);
    char stage[4200] = "", old_dir[4200] = "";
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
    /* everything is staged in a fresh folder and moved into place at the end */
    if ((rc = stage_open(out_dir, stage, sizeof stage, err, errlen)))
        goto done;
    if ((rc = render_device_open(&dev, s, o, err, errlen)))
        goto done;
    for (int si = 0; si < RENDER_SCENE_COUNT; si++)
        if (o->scene_on[si] && (rc = run_scene(&dev, &scenes[si], o, stage, &res[si], err, errlen)))
            goto done;

    /* move the staged pictures into place, then write render.json */
    if ((rc = stage_commit(out_dir, stage, old_dir, sizeof old_dir, err, errlen)))
        goto done;
    char json_path[4300];
    path_join(json_path, sizeof json_path, out_dir, "render.json");
    if (render_write_json(json_path, s, o, res, dev.display_code_error, err, errlen) != 0) {
        rc = EXIT_RUNTIME;
        goto done;
    }
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
