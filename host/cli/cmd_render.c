/* cmd_render.c - `brdfbench render`: the full-image shading passes (sphere grid, Utah
 * teapot, Stanford bunny) with error images, metrics and Mpixel/s; see render.h. */
#include "cli_run.h"
#include "cli_table.h"
#include "commands.h"
#include "exitcodes.h"
#include "outdir.h"
#include "measured.h"
#include "render.h"
#include "usermodel.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RENDER_MAX_MEASURED_FILES 4

/* The image sizes against the device's memory, before any folder or buffer is made. */
static int check_render(struct cl_session *s, void *ctx, char *err, size_t errlen)
{
    const struct render_options *o = ctx;
    int rows = o->scene_on[RENDER_SPHERES] ? o->nmodels : 0;
    int rc = render_check_size(s, "--size", o->width, o->height, rows, err, errlen);
    for (int k = 0; rc == 0 && k < o->ntime_sizes; k++)
        rc = render_check_size(s, "--time-sizes", o->time_w[k], o->time_h[k], rows, err, errlen);
    return rc ? EXIT_USAGE : 0;
}

static int run_render(struct cl_session *s, const char *run_dir, int quiet, void *ctx)
{
    struct render_options *o = ctx;
    o->io = (struct engine_io){ run_dir, quiet };
    if (!quiet)
        printf("device: %s (%s)\n", s->device_name, s->platform_version);
    struct render_result r;
    int rc = render_run(s, o, &r);
    if (rc)
        fprintf(stderr, "brdfbench render: %s\n", r.err);
    render_result_free(&r);
    return rc;
}

static int parse_size(const char *arg, const char *text, int *w, int *h, char *err, size_t errlen)
{
    long lw, lh;
    if (cli_parse_size_wxh(arg, text, RENDER_MAX_SIDE, &lw, &lh, err, errlen) ||
        lw < RENDER_MIN_SIDE || lh < RENDER_MIN_SIDE) {
        snprintf(err, errlen,
                 "%s: '%s' is not WxH with W and H integers in [%d, %d] (W*H*%d bytes must "
                 "also fit the device's memory)",
                 arg, text, RENDER_MIN_SIDE, RENDER_MAX_SIDE, RENDER_DEVICE_BYTES_PER_PIXEL);
        return EXIT_USAGE;
    }
    *w = (int)lw;
    *h = (int)lh;
    return 0;
}

/* Splits a comma-separated list in place; returns the number of items or -1 if more than max. */
static int split_list(char *text, char **items, int max)
{
    int n = 0;
    for (char *p = text;;) {
        char *comma = strchr(p, ',');
        if (comma)
            *comma = '\0';
        if (n == max)
            return -1;
        items[n++] = p;
        if (!comma)
            break;
        p = comma + 1;
    }
    return n;
}

/* A flag's comma-separated value v, copied into buf and split into at most max items; -1 with
 * the message in err when it holds more (`what` names the items in the message). */
static int split_flag_list(const char *flag, const char *v, char *buf, size_t buflen, char **items, int max,
                           const char *what, char *err, size_t errlen)
{
    snprintf(buf, buflen, "%s", v);
    int n = split_list(buf, items, max);
    if (n < 0)
        snprintf(err, errlen, "%s: at most %d %s (got '%s')", flag, max, what, v);
    return n;
}

static int call_scene(const char *flag, const char *v, void *dest, char *err, size_t errlen)
{
    struct render_options *o = dest;
    char buf[1024], *items[32];
    snprintf(buf, sizeof buf, "%s", v);
    int n = strcmp(buf, "all") == 0 ? 0 : split_list(buf, items, 8);
    int on[RENDER_SCENE_COUNT] = { 0 };
    for (int k = 0; k < n; k++) {
        if (strcmp(items[k], "spheres") == 0)
            on[RENDER_SPHERES] = 1;
        else if (strcmp(items[k], "teapot") == 0)
            on[RENDER_TEAPOT] = 1;
        else if (strcmp(items[k], "bunny") == 0)
            on[RENDER_BUNNY] = 1;
        else
            n = -1;
    }
    if (n < 0) {
        snprintf(err, errlen, "%s: '%s' is not a list of spheres, teapot, bunny (or all)", flag, v);
        return EXIT_USAGE;
    }
    if (n != 0)
        memcpy(o->scene_on, on, sizeof on);
    else
        for (int k = 0; k < RENDER_SCENE_COUNT; k++)
            o->scene_on[k] = 1;
    return 0;
}

static int call_size(const char *flag, const char *v, void *dest, char *err, size_t errlen)
{
    struct render_options *o = dest;
    return parse_size(flag, v, &o->width, &o->height, err, errlen);
}

static int call_time_sizes(const char *flag, const char *v, void *dest, char *err, size_t errlen)
{
    struct render_options *o = dest;
    char buf[1024], *items[32];
    if (strcmp(v, "none") == 0) {
        o->ntime_sizes = 0;
        return 0;
    }
    int n = split_flag_list(flag, v, buf, sizeof buf, items, RENDER_MAX_TIME_SIZES, "sizes", err, errlen);
    if (n < 0)
        return EXIT_USAGE;
    for (int k = 0; k < n; k++)
        if (parse_size(flag, items[k], &o->time_w[k], &o->time_h[k], err, errlen))
            return EXIT_USAGE;
    o->ntime_sizes = n;
    return 0;
}

static int call_shininess(const char *flag, const char *v, void *dest, char *err, size_t errlen)
{
    struct render_options *o = dest;
    char buf[1024], *items[RENDER_MAX_COLS + 1];
    int n = split_flag_list(flag, v, buf, sizeof buf, items, RENDER_MAX_COLS, "values", err, errlen);
    if (n < 0)
        return EXIT_USAGE;
    for (int k = 0; k < n; k++)
        if (cli_parse_double(flag, items[k], 1, 10000, &o->sphere_n[k], err, errlen))
            return EXIT_USAGE;
    o->ncols = n;
    return 0;
}

static int call_light(const char *flag, const char *v, void *dest, char *err, size_t errlen)
{
    struct render_options *o = dest;
    if (strcmp(v, "directional") == 0) {
        o->point_light = 0;
    } else if (strcmp(v, "point") == 0) {
        o->point_light = 1;
    } else {
        snprintf(err, errlen, "%s: '%s' is not directional or point", flag, v);
        return EXIT_USAGE;
    }
    return 0;
}

int cmd_render(int argc, char **argv)
{
    /* --device all or a list: one run per device, rows gathered (cli_devices.c) */
    int per_device = cli_per_device(argc, argv, "render", cmd_render, "render.json", "scenes", NULL);
    if (per_device >= 0)
        return per_device;
    char err[1024];
    struct render_options o;
    render_options_default(&o);
    struct cli_engine_run e;
    cli_engine_init(&e, "render", "render.json", run_render, &o);
    e.check = check_render;
    struct cli_model_params mparams = { .count = 0 };
    const char *models_text = NULL, *measured_arg = NULL;
    int models_given = 0;
    char size_range[64], shininess_range[64];
    snprintf(size_range, sizeof size_range, "W and H in [%d, %d]", RENDER_MIN_SIDE, RENDER_MAX_SIDE);
    snprintf(shininess_range, sizeof shininess_range, "each in [1, 10000], at most %d", RENDER_MAX_COLS);

    const struct cli_flag flags[] = {
        { .name = "--scene", .value = "LIST", .kind = CLI_CALL, .call = call_scene, .dest = &o,
          .help = "scenes to render: spheres,teapot,bunny or all", .def = "all" },
        CLI_FLAG_MODELS(&models_text, &models_given, "all; with --model or --model-file, only the user models"),
        { .name = "--size", .value = "WxH", .kind = CLI_CALL, .call = call_size, .dest = &o,
          .help = "image size", .range = size_range, .def = "1920x1080" },
        { .name = "--time-sizes", .value = "LIST", .kind = CLI_CALL, .call = call_time_sizes, .dest = &o,
          .help = "sizes timed, e.g. 1920x1080,3840x2160, or none", .def = "1920x1080,3840x2160" },
        { .name = "--reps", .value = "N", .kind = CLI_INT, .dest = &o.reps, .min = 1, .max = 1000,
          .help = "timed launches per figure" },
        { .name = "--warmup", .value = "N", .kind = CLI_INT, .dest = &o.warmup, .min = 0, .max = 100,
          .help = "untimed launches before them" },
        { .name = "--shininess", .value = "LIST", .kind = CLI_CALL, .call = call_shininess, .dest = &o,
          .help = "the sphere grid's columns, one shininess n each", .range = shininess_range,
          .def = "4,16,64,256,1000" },
        { .name = "--mesh-n", .value = "X", .kind = CLI_DOUBLE, .dest = &o.mesh_n, .min = 1, .max = 10000,
          .help = "shininess n of the teapot and the bunny" },
        { .name = "--tess", .value = "N", .kind = CLI_INT, .dest = &o.tess, .min = 1, .max = 128,
          .help = "teapot quads per patch side" },
        { .name = "--light", .value = "KIND", .kind = CLI_CALL, .call = call_light, .dest = &o,
          .help = "directional or point", .def = "directional" },
        { .name = "--exposure", .value = "X", .kind = CLI_DOUBLE, .dest = &o.exposure, .min = 0.01, .max = 100,
          .help = "display exposure" },
        { .name = "--threshold", .value = "X", .kind = CLI_DOUBLE, .dest = &o.threshold, .min = 0, .max = 1e6,
          .help = "error counted as visible above X" },
        { .name = "--check-pixels", .value = "N", .kind = CLI_INT, .dest = &o.ref_samples, .min = 1, .max = 1000000,
          .help = "pixels per model checked against the double reference" },
        { .name = "--teapot-file", .value = "PATH", .kind = CLI_PATH, .dest = &o.teapot_path,
          .help = "POV-Ray file with bicubic_patch blocks" },
        { .name = "--bunny-file", .value = "PATH", .kind = CLI_PATH, .dest = &o.bunny_path, .help = "OBJ file" },
        CLI_FLAG_MEASURED(&measured_arg),
        { .name = "--no-images", .kind = CLI_SWITCH, .dest = &o.write_images, .set = 0,
          .help = "metrics and timings only, no PNGs" },
        CLI_FLAG_OUT(&e.out_dir, CLI_DEF_OUT "; with --json and no --out, no folder"),
        CLI_FLAG_JSON(&e.json_path),
        CLI_FLAG_QUIET(&e.quiet),
        CLI_FLAGS_USERMODEL,
        CLI_FLAG_MODEL_PARAM(&mparams),
        CLI_FLAGS_DEVICE(&e.dev),
        { .name = "--n", .kind = CLI_RENAMED,
          .help = "the shininess of the teapot and the bunny is --mesh-n X (the sphere grid's is --shininess LIST)" },
        { .name = "--samples", .kind = CLI_RENAMED,
          .help = "the pixels checked against the double reference are --check-pixels N (--samples is the "
                  "accuracy sweeps' samples per zone)" },
    };
    const struct cli_command cmd = {
        .name = "render",
        .about = "  Shades full images with every model on the device: a sphere grid (one row per model,\n"
                 "  one column per shininess), the Utah teapot (povray-examples) and the Stanford bunny\n"
                 "  (glmark2-data). Writes per scene and model the image, an error image against the\n"
                 "  model's reference, metrics, a check against the double host reference, and Mpixel/s\n"
                 "  beside a copy kernel moving the same bytes: DIR/render.json and DIR/render/<scene>/.\n",
        CLI_TABLE(flags),
    };
    int prc = cli_parse(&cmd, argc, argv, NULL, err, sizeof err);
    if (prc)
        return cli_parse_exit(&cmd, prc, err);
    if (!models_text && usermodel_count() > 0)
        models_text = usermodel_names();   /* with a user model and no --models: the user models */
    if (models_text) {
        int n = cli_model_list(models_text, o.models, RENDER_MAX_MODELS, err, sizeof err);
        if (n >= 0)
            n = cli_add_unlisted_user_models(o.models, n, RENDER_MAX_MODELS, err, sizeof err);
        if (n < 0)
            goto usage_error;
        o.nmodels = n;
    }
    if (mparams.count > 0 && cli_apply_model_params(o.models, o.nmodels, &mparams, err, sizeof err))
        goto usage_error;

    struct merl_material mats[RENDER_MAX_MEASURED_FILES];
    if (measured_arg) {
        int lrc = measured_load("--measured", measured_arg, RENDER_MAX_MEASURED_FILES, mats, &o.nmeasured, err,
                                sizeof err);
        if (lrc == EXIT_USAGE)
            goto usage_error;
        if (lrc)
            return lrc;
        for (int i = 0; i < o.nmeasured; ++i)
            o.measured[i] = &mats[i];
    }
    int rc = cli_run_engine(&e);
    if (!rc && !e.quiet && !e.tmp_dir[0])   /* e.quiet: also with the document on stdout */
        printf("written: %s/render.json and %s/render/\n", e.run_dir, e.run_dir);
    for (int i = 0; i < o.nmeasured; ++i)
        merl_free(&mats[i]);
    return rc;

usage_error:
    fprintf(stderr, "brdfbench render: %s\n", err);
    return EXIT_USAGE;
}
