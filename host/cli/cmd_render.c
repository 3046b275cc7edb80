/* cmd_render.c - `brdfbench render`: the full-image shading passes (sphere grid, Utah
 * teapot, Stanford bunny) with error images, metrics and Mpixel/s; see render.h. */
#include "cli.h"
#include "commands.h"
#include "exitcodes.h"
#include "outdir.h"
#include "render.h"
#include "usermodel.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void render_usage(FILE *f)
{
    fprintf(f,
            "usage: brdfbench render [OPTIONS]\n"
            "  Shades full images with every model on the device: a sphere grid (one row per model,\n"
            "  one column per shininess), the Utah teapot (povray-examples) and the Stanford bunny\n"
            "  (glmark2-data). Writes per scene and model the image, an error image against the\n"
            "  model's reference, metrics, a check against the double host reference, and Mpixel/s\n"
            "  beside a copy kernel moving the same bytes: DIR/render.json and DIR/render/<scene>/.\n"
            "  --scene LIST       spheres,teapot,bunny or all (default all)\n"
            "  --models LIST      models with parameters, e.g. phong,cq2,fq:Q=0.7 (default: all)\n"
            "  --size WxH         image size, W and H in [%d, %d] (default 1920x1080)\n"
            "  --time-sizes LIST  sizes timed, e.g. 1920x1080,3840x2160 (the default), or none\n"
            "  --reps N           timed launches per model and size, in [1, 1000] (default 7)\n"
            "  --warmup N         untimed launches before them, in [0, 100] (default 2)\n"
            "  --shininess LIST   sphere grid columns, each in [1, 10000], at most %d\n"
            "                     (default 4,16,64,256,1000)\n"
            "  --n X              shininess of the teapot and the bunny, in [1, 10000] (default 64)\n"
            "  --tess N           teapot quads per patch side, in [1, 128] (default 16)\n"
            "  --light KIND       directional (default) or point\n"
            "  --exposure X       display exposure, in [0.01, 100] (default 1.2)\n"
            "  --threshold X      error counted as visible above X, in [0, 1e6] (default 0.01)\n"
            "  --samples N        pixels per model checked against the double reference, in\n"
            "                     [1, 1000000] (default 4096)\n"
            "  --teapot-file PATH POV-Ray file with bicubic_patch blocks (default %s)\n"
            "  --bunny-file PATH  OBJ file (default %s)\n"
            "  --no-images        metrics and timings only, no PNGs\n"
            "  --out DIR          output folder (default: a new folder results/<date-time>/, with\n"
            "                     results/latest)\n"
            "  --quiet            no progress or tables on stdout\n"
            USERMODEL_OPTIONS_HELP
            DEVICE_OPTIONS_HELP
            DEVICE_LIST_HELP,
            RENDER_MIN_SIDE, RENDER_MAX_SIDE, RENDER_MAX_COLS, RENDER_TEAPOT_PATH,
            RENDER_BUNNY_PATH);
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

/* An integer flag's value in [lo, hi]. Returns 0 or EXIT_USAGE with a message. */
static int parse_int_flag(int argc, char **argv, int *i, const char *flag, long lo, long hi,
                          int *out, char *err, size_t errlen)
{
    long v;
    if (cli_long_value(argc, argv, i, flag, lo, hi, &v, err, errlen))
        return EXIT_USAGE;
    *out = (int)v;
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

int cmd_render(int argc, char **argv)
{
    /* --device all or a list: one run per device, rows gathered (cli_devices.c) */
    int per_device = cli_per_device(argc, argv, "render", cmd_render, "render.json", "scenes");
    if (per_device >= 0)
        return per_device;
    char err[1024];
    struct render_options o;
    render_options_default(&o);
    struct device_options dev;
    device_options_init(&dev);
    const char *models_text = NULL, *out_dir = NULL;
    char buf[1024];
    char *items[32];

    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *v = NULL;
        int d = cli_device_flag(argc, argv, &i, &dev, err, sizeof err);
        if (d == 0)
            d = usermodel_cli_flag(argc, argv, &i, err, sizeof err);
        if (d < 0)
            goto usage_error;
        if (d > 0)
            continue;
        if (strcmp(a, "--help") == 0) {
            render_usage(stdout);
            return EXIT_OK;
        } else if (strcmp(a, "--quiet") == 0) {
            o.verbose = 0;
        } else if (strcmp(a, "--no-images") == 0) {
            o.write_images = 0;
        } else if (cli_flag_is(a, "--scene")) {
            if (!(v = cli_flag_value(argc, argv, &i, "--scene", err, sizeof err)))
                goto usage_error;
            snprintf(buf, sizeof buf, "%s", v);
            int n = strcmp(buf, "all") == 0 ? 0 : split_list(buf, items, 8);
            if (n != 0)
                memset(o.scene_on, 0, sizeof o.scene_on);
            for (int k = 0; k < n; k++) {
                if (strcmp(items[k], "spheres") == 0)
                    o.scene_on[RENDER_SPHERES] = 1;
                else if (strcmp(items[k], "teapot") == 0)
                    o.scene_on[RENDER_TEAPOT] = 1;
                else if (strcmp(items[k], "bunny") == 0)
                    o.scene_on[RENDER_BUNNY] = 1;
                else
                    n = -1;
            }
            if (n < 0) {
                snprintf(err, sizeof err,
                         "--scene: '%s' is not a list of spheres, teapot, bunny (or all)", v);
                goto usage_error;
            }
        } else if (cli_flag_is(a, "--models")) {
            if (!(models_text = cli_flag_value(argc, argv, &i, "--models", err, sizeof err)))
                goto usage_error;
        } else if (cli_flag_is(a, "--size")) {
            if (!(v = cli_flag_value(argc, argv, &i, "--size", err, sizeof err)) ||
                parse_size("--size", v, &o.width, &o.height, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--time-sizes")) {
            if (!(v = cli_flag_value(argc, argv, &i, "--time-sizes", err, sizeof err)))
                goto usage_error;
            if (strcmp(v, "none") == 0) {
                o.ntime_sizes = 0;
                continue;
            }
            snprintf(buf, sizeof buf, "%s", v);
            int n = split_list(buf, items, RENDER_MAX_TIME_SIZES);
            if (n < 0) {
                snprintf(err, sizeof err, "--time-sizes: at most %d sizes (got '%s')",
                         RENDER_MAX_TIME_SIZES, v);
                goto usage_error;
            }
            for (int k = 0; k < n; k++)
                if (parse_size("--time-sizes", items[k], &o.time_w[k], &o.time_h[k], err,
                               sizeof err))
                    goto usage_error;
            o.ntime_sizes = n;
        } else if (cli_flag_is(a, "--reps")) {
            if (parse_int_flag(argc, argv, &i, "--reps", 1, 1000, &o.reps, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--warmup")) {
            if (parse_int_flag(argc, argv, &i, "--warmup", 0, 100, &o.warmup, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--tess")) {
            if (parse_int_flag(argc, argv, &i, "--tess", 1, 128, &o.tess, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--samples")) {
            if (parse_int_flag(argc, argv, &i, "--samples", 1, 1000000, &o.ref_samples, err,
                               sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--shininess")) {
            if (!(v = cli_flag_value(argc, argv, &i, "--shininess", err, sizeof err)))
                goto usage_error;
            snprintf(buf, sizeof buf, "%s", v);
            int n = split_list(buf, items, RENDER_MAX_COLS);
            if (n < 0) {
                snprintf(err, sizeof err, "--shininess: at most %d values (got '%s')",
                         RENDER_MAX_COLS, v);
                goto usage_error;
            }
            for (int k = 0; k < n; k++)
                if (cli_parse_double("--shininess", items[k], 1, 10000, &o.sphere_n[k], err,
                                     sizeof err))
                    goto usage_error;
            o.ncols = n;
        } else if (cli_flag_is(a, "--n")) {
            if (cli_double_value(argc, argv, &i, "--n", 1, 10000, &o.mesh_n, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--exposure")) {
            if (cli_double_value(argc, argv, &i, "--exposure", 0.01, 100, &o.exposure, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--threshold")) {
            if (cli_double_value(argc, argv, &i, "--threshold", 0, 1e6, &o.threshold, err, sizeof err))
                goto usage_error;
        } else if (cli_flag_is(a, "--light")) {
            if (!(v = cli_flag_value(argc, argv, &i, "--light", err, sizeof err)))
                goto usage_error;
            if (strcmp(v, "directional") == 0) {
                o.point_light = 0;
            } else if (strcmp(v, "point") == 0) {
                o.point_light = 1;
            } else {
                snprintf(err, sizeof err, "--light: '%s' is not directional or point", v);
                goto usage_error;
            }
        } else if (cli_flag_is(a, "--teapot-file")) {
            if (!(o.teapot_path = cli_flag_value(argc, argv, &i, "--teapot-file", err, sizeof err)))
                goto usage_error;
        } else if (cli_flag_is(a, "--bunny-file")) {
            if (!(o.bunny_path = cli_flag_value(argc, argv, &i, "--bunny-file", err, sizeof err)))
                goto usage_error;
        } else if (cli_flag_is(a, "--out")) {
            if (!(out_dir = cli_path_value(argc, argv, &i, "--out", err, sizeof err)))
                goto usage_error;
        } else {
            snprintf(err, sizeof err, "unknown option '%s' (see brdfbench render --help)", a);
            goto usage_error;
        }
    }
    if (!models_text && usermodel_count() > 0)
        models_text = usermodel_names();   /* with a user model and no --models: the user models */
    if (models_text) {
        int n = model_spec_list_parse(models_text, o.models, RENDER_MAX_MODELS, err, sizeof err);
        if (n < 0)
            goto usage_error;
        o.nmodels = n;
    }

    struct cl_session s;
    int rc = clsession_open(&s, dev.platform, dev.device, err, sizeof err);
    if (rc) {
        fprintf(stderr, "brdfbench render: %s\n", err);
        return rc;
    }
    /* sizes against the device's memory before anything is allocated */
    int rows = o.scene_on[RENDER_SPHERES] ? o.nmodels : 0;
    rc = render_check_size(&s, "--size", o.width, o.height, rows, err, sizeof err);
    for (int k = 0; rc == 0 && k < o.ntime_sizes; k++)
        rc = render_check_size(&s, "--time-sizes", o.time_w[k], o.time_h[k], rows, err,
                               sizeof err);
    if (rc) {
        clsession_close(&s);
        goto usage_error;
    }
    char run_dir[4096];
    if (out_dir) {
        snprintf(run_dir, sizeof run_dir, "%s", out_dir);
    } else if (outdir_prepare("results", NULL, err, sizeof err) != 0 ||
               outdir_new_run("results", run_dir, sizeof run_dir, err, sizeof err) != 0) {
        fprintf(stderr, "brdfbench render: %s\n", err);
        clsession_close(&s);
        return EXIT_RUNTIME;
    }
    if (o.verbose)
        printf("device: %s (%s)\n", s.device_name, s.platform_version);
    rc = render_run(&s, &o, run_dir, NULL, err, sizeof err);
    if (rc == 0 && !out_dir &&
        outdir_set_latest("results", run_dir, err, sizeof err) != 0)
        rc = EXIT_RUNTIME;
    clsession_close(&s);
    if (rc) {
        fprintf(stderr, "brdfbench render: %s\n", err);
        return rc;
    }
    if (o.verbose)
        printf("written: %s/render.json and %s/render/\n", run_dir, run_dir);
    return EXIT_OK;

usage_error:
    fprintf(stderr, "brdfbench render: %s\n", err);
    return EXIT_USAGE;
}
