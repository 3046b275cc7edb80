/* cli_devices.c - `--device all` and device lists for throughput, accuracy and render: the
 * command runs once per device, each into RUN/devices/<k>/ (its complete outputs), and the
 * rows of those result files are gathered into RUN/<file>, each row tagged with its device
 * ("device": the device's name, with " #k" where the list names the same device again), with
 * the list of devices in context.devices. `brdfbench compare RUN` lays them side by side. */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"
#include "cli_run.h"
#include "cli_table.h"
#include "clsession.h"
#include "exitcodes.h"
#include "jsonr.h"
#include "jsonw.h"
#include "outdir.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The value of flag `name` in argv ("--name V" or "--name=V"), or NULL. */
static const char *flag_value(int argc, char **argv, const char *name)
{
    size_t n = strlen(name);
    const char *v = NULL;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], name) == 0 && i + 1 < argc)
            v = argv[++i];
        else if (strncmp(argv[i], name, n) == 0 && argv[i][n] == '=')
            v = argv[i] + n + 1;
    }
    return v;
}

/* A device value that is one index runs as before; "all", a list or P:D run per device. */
int cli_is_device_list(const char *v)
{
    return v && (strcmp(v, "all") == 0 || strchr(v, ',') || strchr(v, ':'));
}

/* Writes a parsed JSON value back (numbers round-trip through %.17g). */
static void jw_value(struct jw *w, const struct jr_value *v)
{
    switch (v->type) {
    case JR_NULL: jw_null(w); break;
    case JR_BOOL: jw_bool(w, v->num != 0); break;
    case JR_NUM: jw_num(w, v->num); break;
    case JR_STR: jw_str(w, v->str); break;
    case JR_ARR:
        jw_arr_begin(w);
        for (size_t i = 0; i < v->count; ++i)
            jw_value(w, &v->items[i]);
        jw_arr_end(w);
        break;
    case JR_OBJ:
        jw_obj_begin(w);
        for (size_t i = 0; i < v->count; ++i) {
            jw_key(w, v->keys[i]);
            jw_value(w, &v->items[i]);
        }
        jw_obj_end(w);
        break;
    }
}

static const char *member_str(const struct jr_value *obj, const char *key)
{
    const struct jr_value *v = jr_get(obj, key);
    return v && v->type == JR_STR ? v->str : "";
}

/* RUN/<file> from RUN/devices/<k>/<file>: the first file with its rows replaced by every
   file's rows, each tagged, and context.devices. */
static int merge_devices(const char *run_dir, const char *file, const char *rows_key, const struct cl_device_ref *refs,
                         int n, char *err, size_t errlen)
{
    struct jr_doc *docs = calloc((size_t)n, sizeof *docs);
    char (*tags)[300] = calloc((size_t)n, sizeof *tags);
    int parsed = 0, rc = 2;
    if (!docs || !tags) {
        snprintf(err, errlen, "out of memory");
        goto done;
    }
    for (int k = 0; k < n; ++k, ++parsed) {
        char path[4200];
        snprintf(path, sizeof path, "%s/devices/%d/%s", run_dir, k + 1, file);
        if (jr_parse_file(path, &docs[k], err, errlen))
            goto done;
        const struct jr_value *rows = jr_get(&docs[k].root, rows_key);
        if (!rows || rows->type != JR_ARR) {
            snprintf(err, errlen, "%.900s: no \"%s\" array", path, rows_key);
            ++parsed;
            goto done;
        }
        snprintf(tags[k], sizeof tags[k], "%s", member_str(jr_get(&docs[k].root, "context"), "device"));
    }
    /* the same device named twice: each later one gets its place in the list */
    for (int k = 1; k < n; ++k)
        for (int j = 0; j < k; ++j)
            if (strcmp(member_str(jr_get(&docs[j].root, "context"), "device"),
                       member_str(jr_get(&docs[k].root, "context"), "device")) == 0) {
                char t[300];
                snprintf(t, sizeof t, "%.280s #%d", tags[k], k + 1);
                snprintf(tags[k], sizeof tags[k], "%s", t);
                break;
            }
    struct jw w;
    jw_init(&w);
    const struct jr_value *root = &docs[0].root;
    jw_obj_begin(&w);
    for (size_t i = 0; i < root->count; ++i) {
        jw_key(&w, root->keys[i]);
        if (strcmp(root->keys[i], "context") == 0) {
            const struct jr_value *ctx = &root->items[i];
            jw_obj_begin(&w);
            for (size_t c = 0; c < ctx->count; ++c) {
                jw_key(&w, ctx->keys[c]);
                jw_value(&w, &ctx->items[c]);
            }
            jw_kv_arr(&w, "devices");
            for (int k = 0; k < n; ++k) {
                const struct jr_value *dc = jr_get(&docs[k].root, "context");
                char idx[32], sub[64];
                snprintf(idx, sizeof idx, "%d:%d", refs[k].platform, refs[k].device);
                snprintf(sub, sizeof sub, "devices/%d/%s", k + 1, file);
                jw_obj_begin(&w);
                jw_kv_str(&w, "tag", tags[k]);
                jw_kv_str(&w, "index", idx);
                jw_kv_str(&w, "file", sub);
                static const char *const keys[] = { "device", "platform", "platform_version", "device_version",
                                                    "driver_version", "compute_units" };
                for (size_t j = 0; j < sizeof keys / sizeof keys[0]; ++j)
                    if (jr_get(dc, keys[j])) {
                        jw_key(&w, keys[j]);
                        jw_value(&w, jr_get(dc, keys[j]));
                    }
                /* each device's own settings (its work-items, the runner's record) and, for
                   throughput, its measured peak: they differ by device */
                static const char *const own[] = { "throughput", "grid" };
                for (size_t j = 0; j < sizeof own / sizeof own[0]; ++j)
                    if (jr_get(dc, own[j])) {
                        jw_key(&w, own[j]);
                        jw_value(&w, jr_get(dc, own[j]));
                    }
                if (jr_get(&docs[k].root, "peak")) {
                    jw_key(&w, "peak");
                    jw_value(&w, jr_get(&docs[k].root, "peak"));
                }
                jw_obj_end(&w);
            }
            jw_arr_end(&w);
            jw_kv_str(&w, "devices_note", "one run per device, each complete in its devices/<k>/ folder; the rows "
                                          "here are all of theirs, tagged with \"device\"; each device's settings and "
                                          "peak are in its entry; other sections are the first device's");
            jw_obj_end(&w);
        } else if (strcmp(root->keys[i], rows_key) == 0) {
            jw_arr_begin(&w);
            for (int k = 0; k < n; ++k) {
                const struct jr_value *rows = jr_get(&docs[k].root, rows_key);
                for (size_t r = 0; r < rows->count; ++r) {
                    const struct jr_value *row = &rows->items[r];
                    jw_obj_begin(&w);
                    jw_kv_str(&w, "device", tags[k]);
                    for (size_t m = 0; row->type == JR_OBJ && m < row->count; ++m) {
                        if (strcmp(row->keys[m], "device") == 0)
                            continue;
                        jw_key(&w, row->keys[m]);
                        jw_value(&w, &row->items[m]);
                    }
                    jw_obj_end(&w);
                }
            }
            jw_arr_end(&w);
        } else {
            jw_value(&w, &root->items[i]);
        }
    }
    jw_obj_end(&w);
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", run_dir, file);
    rc = jw_write_file(&w, path, err, errlen) ? EXIT_RUNTIME : 0;
    jw_free(&w);
done:
    for (int k = 0; k < parsed && k < n; ++k)
        jr_free(&docs[k]);
    free(docs);
    free(tags);
    return rc;
}

int cli_per_device(int argc, char **argv, const char *command, int (*cmd)(int, char **), const char *file,
                   const char *rows_key)
{
    const char *list = flag_value(argc, argv, "--device");
    for (int i = 1; i < argc; ++i)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0)
            return -1;
    if (!cli_is_device_list(list))
        return -1;
    char err[1200];
    long platform = -1;
    const char *pv = flag_value(argc, argv, "--platform");
    if (pv && cli_parse_long("--platform", pv, 0, 63, &platform, err, sizeof err)) {
        fprintf(stderr, "brdfbench %s: %s\n", command, err);
        return EXIT_USAGE;
    }
    struct cl_device_ref refs[CL_MAX_DEVICE_REFS];
    int n = clsession_device_list(list, (int)platform, refs, CL_MAX_DEVICE_REFS, err, sizeof err);
    if (n < 0) {
        fprintf(stderr, "brdfbench %s: %s\n", command, err);
        return -n;
    }
    const char *out_dir = flag_value(argc, argv, "--out");
    const char *json_path = flag_value(argc, argv, "--json"), *csv_path = flag_value(argc, argv, "--csv");
    int quiet = 0;
    for (int i = 1; i < argc; ++i)
        quiet |= strcmp(argv[i], "--quiet") == 0;
    /* --json without --out: the gathered rows only, made in a temporary folder (as one device's
       run makes its document); the devices' runs write no document of their own */
    if (csv_path && !out_dir) {
        fprintf(stderr, "brdfbench %s: --csv: the rows of several devices are gathered into %s only (accepted: "
                "--json FILE|-, or --out DIR for each device's CSV)\n", command, file);
        return EXIT_USAGE;
    }
    int temp = json_path && !out_dir;
    struct stat st;
    int existed = out_dir && stat(out_dir, &st) == 0;
    char run_dir[4096], devices[4200], sub[4300];
    if (temp) {
        if (cli_run_check_documents(command, json_path, NULL))
            return EXIT_RUNTIME;
        if (cli_temp_dir(run_dir, sizeof run_dir, err, sizeof err)) {
            fprintf(stderr, "brdfbench %s: %s\n", command, err);
            return EXIT_RUNTIME;
        }
        outdir_own(run_dir);   /* removed at the end, and by a deadline or signal */
        outdir_confine(run_dir);
    } else if (outdir_for_command(out_dir, run_dir, sizeof run_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench %s: %s\n", command, err);
        return EXIT_RUNTIME;
    }
    if (path_join(devices, sizeof devices, run_dir, "devices") || outdir_prepare(devices, "--out", err, sizeof err)) {
        fprintf(stderr, "brdfbench %s: %s\n", command, err);
        return EXIT_RUNTIME;
    }
    /* argv without the device and output flags, then --platform P --device D --out SUB */
    char **av = calloc((size_t)argc + 8, sizeof *av);
    if (!av)
        return EXIT_RUNTIME;
    int ac = 0;
    for (int i = 0; i < argc; ++i) {
        int takes = 0;
        static const char *const drop[] = { "--device", "--platform", "--out", "--json", "--csv" };
        for (size_t j = 0; j < (temp ? 5u : 3u); ++j)
            if (strcmp(argv[i], drop[j]) == 0)
                takes = 2;
            else if (strncmp(argv[i], drop[j], strlen(drop[j])) == 0 && argv[i][strlen(drop[j])] == '=')
                takes = 1;
        if (takes) {
            i += takes - 1;
            continue;
        }
        av[ac++] = argv[i];
    }
    /* only the gathered document is kept: the devices' runs print no table of files that go */
    if (temp)
        av[ac++] = "--quiet";
    char pbuf[16], dbuf[16];
    av[ac] = "--platform";
    av[ac + 1] = pbuf;
    av[ac + 2] = "--device";
    av[ac + 3] = dbuf;
    av[ac + 4] = "--out";
    av[ac + 5] = sub;
    av[ac + 6] = NULL;
    int rc = 0;
    for (int k = 0; k < n && !rc; ++k) {
        snprintf(pbuf, sizeof pbuf, "%d", refs[k].platform);
        snprintf(dbuf, sizeof dbuf, "%d", refs[k].device);
        snprintf(sub, sizeof sub, "%s/%d", devices, k + 1);
        if (!quiet)
            fprintf(stderr, "%s: device %d of %d (platform %d, device %d) into %s\n", command, k + 1, n,
                    refs[k].platform, refs[k].device, sub);
        rc = cmd(ac + 6, av);
        if (rc == EXIT_USAGE && k == 0) {
            /* a bad flag: nothing measured, so nothing is left behind */
            rmdir(sub);
            rmdir(devices);
            if (!existed)
                rmdir(run_dir);
        }
    }
    free(av);
    if (rc) {
        if (temp)
            outdir_remove_own();
        return rc;
    }
    rc = merge_devices(run_dir, file, rows_key, refs, n, err, sizeof err);
    if (rc) {
        fprintf(stderr, "brdfbench %s: %s\n", command, err);
        if (temp)
            outdir_remove_own();
        return EXIT_RUNTIME;
    }
    if (temp) {
        char src[4300];
        path_join(src, sizeof src, run_dir, file);
        rc = cli_deliver(src, "--json", json_path, err, sizeof err) ? EXIT_RUNTIME : 0;
        if (rc)
            fprintf(stderr, "brdfbench %s: %s\n", command, err);
        outdir_remove_own();   /* the temporary folder with the devices' runs */
        if (!rc && !quiet && !cli_is_stdout(json_path))
            printf("written: %s (%d devices, rows tagged with \"device\")\n", json_path, n);
        return rc;
    }
    if (!out_dir && outdir_set_latest("results", run_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench %s: %s\n", command, err);
        return EXIT_RUNTIME;
    }
    if (!quiet)
        printf("written: %s/%s (%d devices, rows tagged with \"device\"; each device's own outputs in %s/)\n",
               run_dir, file, n, devices);
    return 0;
}

/* One side of an A/B run: RUN/ab/<side>/throughput.json with the rows of `variant` renamed to
   the default variant (so that compare matches them with the other side's), the context's
   build options those of the side, and context.ab saying what the document is. */
static int write_ab_side(const char *run_dir, const struct jr_doc *d, const char *side, const char *variant,
                         const char *options, char *err, size_t errlen)
{
    char dir[4200], path[4300];
    snprintf(dir, sizeof dir, "%s/ab/%s", run_dir, side);
    if (outdir_prepare(dir, "--ab-options", err, errlen))
        return EXIT_RUNTIME;
    const struct jr_value *root = &d->root;
    struct jw w;
    jw_init(&w);
    jw_obj_begin(&w);
    for (size_t i = 0; i < root->count; ++i) {
        const char *key = root->keys[i];
        const struct jr_value *v = &root->items[i];
        jw_key(&w, key);
        if (strcmp(key, "context") == 0) {
            jw_obj_begin(&w);
            for (size_t c = 0; c < v->count; ++c) {
                jw_key(&w, v->keys[c]);
                if (strcmp(v->keys[c], "build_options") == 0)
                    jw_str(&w, options);
                else
                    jw_value(&w, &v->items[c]);
            }
            jw_kv_obj(&w, "ab");
            jw_kv_str(&w, "side", side);
            jw_kv_str(&w, "build_options", options);
            jw_kv_str(&w, "note", "one side of an A/B run: both sides' rows were timed in the same interleaved rounds "
                                  "of one process (the full run is ../../throughput.json)");
            jw_obj_end(&w);
            jw_obj_end(&w);
        } else if (strcmp(key, "results") == 0 && v->type == JR_ARR) {
            jw_arr_begin(&w);
            for (size_t r = 0; r < v->count; ++r) {
                const struct jr_value *row = &v->items[r];
                if (strcmp(member_str(row, "variant"), variant) != 0)
                    continue;
                jw_obj_begin(&w);
                for (size_t m = 0; row->type == JR_OBJ && m < row->count; ++m) {
                    jw_key(&w, row->keys[m]);
                    if (strcmp(row->keys[m], "variant") == 0)
                        jw_str(&w, "default");
                    else
                        jw_value(&w, &row->items[m]);
                }
                jw_obj_end(&w);
            }
            jw_arr_end(&w);
        } else {
            jw_value(&w, v);
        }
    }
    jw_obj_end(&w);
    snprintf(path, sizeof path, "%s/throughput.json", dir);
    int rc = jw_write_file(&w, path, err, errlen) ? EXIT_RUNTIME : 0;
    jw_free(&w);
    return rc;
}

int cli_write_ab(const char *run_dir, const char *ab_options, char *err, size_t errlen)
{
    char path[4200];
    struct jr_doc d;
    snprintf(path, sizeof path, "%s/throughput.json", run_dir);
    if (jr_parse_file(path, &d, err, errlen))
        return EXIT_RUNTIME;
    const char *base = member_str(jr_get(&d.root, "context"), "build_options");
    char b_options[1024];
    snprintf(b_options, sizeof b_options, "%s%s%s", base, *base ? " " : "", ab_options);
    int rc = write_ab_side(run_dir, &d, "a", "default", base, err, errlen);
    if (!rc)
        rc = write_ab_side(run_dir, &d, "b", "ab", b_options, err, errlen);
    jr_free(&d);
    return rc;
}
