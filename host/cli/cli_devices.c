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
#include "infile.h"
#include "jsonw.h"
#include "mdbuf.h"
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

typedef char device_tag[300];

/* The gathered file's "rows" member (rdoc.h): the first device's context lines, as the file's
   other sections are the first device's; each device's own lines (its settings, its machine
   record) under "devices" where there are several; every device's rows, each tagged with its
   device. */
static void merged_rows_member(struct jw *w, const struct jr_doc *docs, int n, const device_tag *tags)
{
    const struct jr_value *first = jr_get(&docs[0].root, "rows");
    jw_obj_begin(w);
    for (size_t i = 0; i < first->count; ++i)
        if (strcmp(first->keys[i], "devices") != 0 && strcmp(first->keys[i], "rows") != 0) {
            jw_key(w, first->keys[i]);
            jw_value(w, &first->items[i]);
        }
    jw_kv_arr(w, "devices");
    for (int k = 0; n >= 2 && k < n; ++k) {
        const struct jr_value *ctx = jr_get(jr_get(&docs[k].root, "rows"), "context");
        jw_obj_begin(w);
        jw_kv_str(w, "name", tags[k]);
        jw_kv_obj(w, "context");
        for (size_t c = 0; ctx && ctx->type == JR_OBJ && c < ctx->count; ++c) {
            jw_key(w, ctx->keys[c]);
            jw_value(w, &ctx->items[c]);
        }
        jw_obj_end(w);
        jw_obj_end(w);
    }
    jw_arr_end(w);
    jw_kv_arr(w, "rows");
    for (int k = 0; k < n; ++k) {
        const struct jr_value *rows = jr_get(jr_get(&docs[k].root, "rows"), "rows");
        for (size_t r = 0; rows && rows->type == JR_ARR && r < rows->count; ++r) {
            const struct jr_value *row = &rows->items[r];
            jw_obj_begin(w);
            jw_kv_str(w, "device", tags[k]);
            for (size_t m = 0; row->type == JR_OBJ && m < row->count; ++m)
                if (strcmp(row->keys[m], "device") != 0) {
                    jw_key(w, row->keys[m]);
                    jw_value(w, &row->items[m]);
                }
            jw_obj_end(w);
        }
    }
    jw_arr_end(w);
    jw_obj_end(w);
}

/* RUN/<file> from RUN/devices/<k>/<file>: the first file with its rows replaced by every
   file's rows, each tagged, and context.devices; tags[k] receives device k's tag. */
static int merge_devices(const char *run_dir, const char *file, const char *rows_key, const struct cl_device_ref *refs,
                         int n, device_tag *tags, char *err, size_t errlen)
{
    struct jr_doc *docs = calloc((size_t)n, sizeof *docs);
    int parsed = 0, rc = 2;
    if (!docs) {
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
        } else if (strcmp(root->keys[i], "rows") == 0 && root->items[i].type == JR_OBJ) {
            merged_rows_member(&w, docs, n, tags);
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
    return rc;
}

/* Where a CSV record that starts at p ends: at the first newline outside double quotes (RFC
   4180: a quoted field may hold one), or at the text's end. */
static const char *csv_record_end(const char *p)
{
    int quoted = 0;
    for (; *p && (quoted || *p != '\n'); ++p)
        quoted ^= *p == '"';
    return p;
}

/* The length of the record [p, e) without a '\r' before its newline. */
static size_t csv_record_len(const char *p, const char *e)
{
    return (size_t)(e - p) - (e > p && e[-1] == '\r');
}

/* RUN/<csv> from RUN/devices/<k>/<csv>: the header with a first column device, then every
   device's rows in turn, each with its device's tag (CSV-quoted) in front. The devices' files
   must have the same header (one command, one set of flags). */
static int gather_csv(const char *run_dir, const char *csv, const device_tag *tags, int n, char *err,
                      size_t errlen)
{
    struct md_buf b;
    md_init(&b);
    char path[4300], *first = NULL;
    size_t first_len = 0;
    int rc = EXIT_RUNTIME;
    for (int k = 0; k < n; ++k) {
        char *buf, why[256];
        size_t len;
        snprintf(path, sizeof path, "%s/devices/%d/%s", run_dir, k + 1, csv);
        if (infile_read(path, 0, (size_t)1 << 30, &buf, &len, why, sizeof why)) {
            snprintf(err, errlen, "%.900s: cannot read: %s", path, why);
            goto done;
        }
        const char *e = csv_record_end(buf);
        size_t hl = csv_record_len(buf, e);
        if (k == 0) {
            md_printf(&b, "device,%.*s\n", (int)hl, buf);
            first = buf;
            first_len = hl;
        } else if (hl != first_len || memcmp(buf, first, hl) != 0) {
            snprintf(err, errlen, "%.900s: its header differs from devices/1/%s's", path, csv);
            free(buf);
            goto done;
        }
        for (const char *p = *e ? e + 1 : e; *p; p = *e ? e + 1 : e) {
            e = csv_record_end(p);
            size_t l = csv_record_len(p, e);
            if (l == 0)
                continue;   /* a blank line is no row */
            md_csv_text(&b, tags[k]);
            md_printf(&b, ",%.*s\n", (int)l, p);
        }
        if (buf != first)
            free(buf);
    }
    if (b.failed) {
        snprintf(err, errlen, "out of memory");
        goto done;
    }
    path_join(path, sizeof path, run_dir, csv);
    rc = write_file_atomic(path, b.s, b.len, err, errlen) ? EXIT_RUNTIME : 0;
done:
    free(first);
    md_free(&b);
    return rc;
}

/* What one --device all run was asked for. */
struct per_device {
    const char *command, *file, *rows_key, *csv;   /* csv: the command's CSV, or NULL */
    const char *out_dir, *json_path, *csv_path;
    int quiet, temp, existed;
    char run_dir[4096], devices[4200];
};

/* argv without the device and output flags (--json and --csv too: the gathered files are
   delivered there), --quiet where only documents are kept or one goes to standard output, then
   room for --platform P --device D --out SUB (set by the caller at *ac .. *ac + 5). */
static char **device_argv(int argc, char **argv, const struct per_device *pd, int *ac)
{
    char **av = calloc((size_t)argc + 8, sizeof *av);
    if (!av)
        return NULL;
    static const char *const drop[] = { "--device", "--platform", "--out", "--json", "--csv" };
    *ac = 0;
    for (int i = 0; i < argc; ++i) {
        int takes = 0;
        for (size_t j = 0; j < sizeof drop / sizeof drop[0]; ++j)
            if (strcmp(argv[i], drop[j]) == 0)
                takes = 2;
            else if (strncmp(argv[i], drop[j], strlen(drop[j])) == 0 && argv[i][strlen(drop[j])] == '=')
                takes = 1;
        if (takes) {
            i += takes - 1;
            continue;
        }
        av[(*ac)++] = argv[i];
    }
    if (pd->temp || cli_is_stdout(pd->json_path) || cli_is_stdout(pd->csv_path))
        av[(*ac)++] = "--quiet";
    return av;
}

/* Runs cmd once per device into DEVICES/<k>; a bad flag (exit 2 on the first) leaves nothing. */
static int run_devices(int argc, char **argv, int (*cmd)(int, char **), const struct per_device *pd,
                       const struct cl_device_ref *refs, int n)
{
    int ac;
    char **av = device_argv(argc, argv, pd, &ac);
    if (!av)
        return EXIT_RUNTIME;
    char pbuf[16], dbuf[16], sub[4300];
    char *tail[] = { "--platform", pbuf, "--device", dbuf, "--out", sub, NULL };
    memcpy(av + ac, tail, sizeof tail);
    int rc = 0;
    for (int k = 0; k < n && !rc; ++k) {
        snprintf(pbuf, sizeof pbuf, "%d", refs[k].platform);
        snprintf(dbuf, sizeof dbuf, "%d", refs[k].device);
        snprintf(sub, sizeof sub, "%s/%d", pd->devices, k + 1);
        if (!pd->quiet)
            fprintf(stderr, "%s: device %d of %d (platform %d, device %d) into %s\n", pd->command, k + 1, n,
                    refs[k].platform, refs[k].device, sub);
        rc = cmd(ac + 6, av);
        if (rc == EXIT_USAGE && k == 0) {
            rmdir(sub);
            rmdir(pd->devices);
            if (!pd->existed)
                rmdir(pd->run_dir);
        }
    }
    free(av);
    return rc;
}

/* The gathered files (JSON, and CSV where the command writes one) in RUN, then copied to
   --json and --csv where given. */
static int gather_and_deliver(const struct per_device *pd, const struct cl_device_ref *refs, int n)
{
    char err[1200], src[4300];
    device_tag *tags = calloc((size_t)n, sizeof *tags);
    int rc = tags ? merge_devices(pd->run_dir, pd->file, pd->rows_key, refs, n, tags, err, sizeof err) : 2;
    if (!tags)
        snprintf(err, sizeof err, "out of memory");
    if (!rc && pd->csv)
        rc = gather_csv(pd->run_dir, pd->csv, tags, n, err, sizeof err);
    free(tags);
    if (!rc && pd->json_path)
        rc = path_join(src, sizeof src, pd->run_dir, pd->file) || cli_deliver(src, "--json", pd->json_path, err, sizeof err);
    if (!rc && pd->csv_path)
        rc = path_join(src, sizeof src, pd->run_dir, pd->csv) || cli_deliver(src, "--csv", pd->csv_path, err, sizeof err);
    if (rc) {
        fprintf(stderr, "brdfbench %s: %s\n", pd->command, err);
        return EXIT_RUNTIME;
    }
    return 0;
}

/* The "written:" lines of a finished run. */
static void print_written(const struct per_device *pd, int n)
{
    if (pd->quiet)
        return;
    const char *paths[] = { pd->json_path, pd->csv_path };
    for (int i = 0; i < 2; ++i)
        if (paths[i] && !cli_is_stdout(paths[i]))
            printf("written: %s (%d devices, rows tagged with \"device\")\n", paths[i], n);
    if (pd->temp)
        return;
    char csv[4300] = "";
    if (pd->csv)
        snprintf(csv, sizeof csv, ", %s/%s", pd->run_dir, pd->csv);
    printf("written: %s/%s%s (%d devices, rows tagged with \"device\"; each device's own outputs in %s/)\n",
           pd->run_dir, pd->file, csv, n, pd->devices);
}

/* The run folder: a temporary one where only --json/--csv documents are asked for, else --out
   or a new results/<date-time>; and its devices/ folder. */
static int open_run_dir(struct per_device *pd, char *err, size_t errlen)
{
    struct stat st;
    pd->existed = pd->out_dir && stat(pd->out_dir, &st) == 0;
    if (pd->temp) {
        if (cli_temp_dir(pd->run_dir, sizeof pd->run_dir, err, errlen))
            return EXIT_RUNTIME;
        outdir_own(pd->run_dir);   /* removed at the end, and by a deadline or signal */
        outdir_confine(pd->run_dir);
    } else if (outdir_for_command(pd->out_dir, pd->run_dir, sizeof pd->run_dir, err, errlen)) {
        return EXIT_RUNTIME;
    }
    if (path_join(pd->devices, sizeof pd->devices, pd->run_dir, "devices") ||
        outdir_prepare(pd->devices, "--out", err, errlen))
        return EXIT_RUNTIME;
    return 0;
}

/* The flags cli_per_device reads; 0, or EXIT_USAGE with err filled. */
static int read_flags(int argc, char **argv, struct per_device *pd, long *platform, char *err, size_t errlen)
{
    const char *pv = flag_value(argc, argv, "--platform");
    if (pv && cli_parse_long("--platform", pv, 0, 63, platform, err, errlen))
        return EXIT_USAGE;
    pd->out_dir = flag_value(argc, argv, "--out");
    pd->json_path = flag_value(argc, argv, "--json");
    pd->csv_path = flag_value(argc, argv, "--csv");
    for (int i = 1; i < argc; ++i)
        pd->quiet |= strcmp(argv[i], "--quiet") == 0;
    if (pd->csv_path && !pd->csv) {
        snprintf(err, errlen, "--csv: %s writes no CSV; the rows of several devices are gathered into %s "
                 "(accepted: --json FILE|-, --out DIR)", pd->command, pd->file);
        return EXIT_USAGE;
    }
    if (cli_is_stdout(pd->json_path) && pd->csv && cli_is_stdout(pd->csv_path)) {
        snprintf(err, errlen, "--json - and --csv -: one document at a time on standard output");
        return EXIT_USAGE;
    }
    /* --json or --csv without --out: the gathered files only, made in a temporary folder */
    pd->temp = (pd->json_path || pd->csv_path) && !pd->out_dir;
    return 0;
}

int cli_per_device(int argc, char **argv, const char *command, int (*cmd)(int, char **), const char *file,
                   const char *rows_key, const char *csv)
{
    const char *list = flag_value(argc, argv, "--device");
    for (int i = 1; i < argc; ++i)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0)
            return -1;
    if (!cli_is_device_list(list))
        return -1;
    char err[1200];
    long platform = -1;
    struct per_device pd = { .command = command, .file = file, .rows_key = rows_key, .csv = csv };
    if (read_flags(argc, argv, &pd, &platform, err, sizeof err)) {
        fprintf(stderr, "brdfbench %s: %s\n", command, err);
        return EXIT_USAGE;
    }
    struct cl_device_ref refs[CL_MAX_DEVICE_REFS];
    int n = clsession_device_list(list, (int)platform, refs, CL_MAX_DEVICE_REFS, err, sizeof err);
    if (n < 0) {
        fprintf(stderr, "brdfbench %s: %s\n", command, err);
        return -n;
    }
    if (cli_run_check_documents(command, pd.json_path, pd.csv_path))
        return EXIT_RUNTIME;
    if (open_run_dir(&pd, err, sizeof err)) {
        fprintf(stderr, "brdfbench %s: %s\n", command, err);
        return EXIT_RUNTIME;
    }
    int rc = run_devices(argc, argv, cmd, &pd, refs, n);
    if (!rc)
        rc = gather_and_deliver(&pd, refs, n);
    if (pd.temp) {
        outdir_remove_own();   /* the temporary folder with the devices' runs */
    } else if (!rc && !pd.out_dir && outdir_set_latest("results", pd.run_dir, err, sizeof err)) {
        fprintf(stderr, "brdfbench %s: %s\n", command, err);
        return EXIT_RUNTIME;
    }
    if (!rc)
        print_written(&pd, n);
    return rc;
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
