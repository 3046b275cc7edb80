/* report_run.c - run.json, the record `all` keeps of its run for report.md (report.h): the
 * command, the folder's name, the wall time, the step list, each part's state, and the
 * pictures of the sweep, heatmaps and plots with their captions; the context block carries
 * the date, the device and the revision. The reader below gives it back to report.c. */
#define _POSIX_C_SOURCE 200809L
#include "report.h"
#include "report_run.h"

#include "context.h"
#include "jsonw.h"
#include "outdir.h"
#include "plots.h"
#include "schemas.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

static const char *const part_names[REPORT_PART_COUNT] = {
    "claims", "fit", "throughput", "images", "frontier", "measured",
};
static const char *const section_names[REPORT_SECTION_COUNT] = {
    "heatmaps", "plots", "throughput", "images",
};

const char *report_part_page(int part)
{
    static const char *const pages[REPORT_PART_COUNT] = {
        "claims.md", NULL, "throughput.md", NULL, "frontier.md", "measured.md",
    };
    return part >= 0 && part < REPORT_PART_COUNT ? pages[part] : NULL;
}

int report_run_write(const char *run_dir, const struct report_run *run, const struct cl_session *s, char *err,
                     size_t errlen)
{
    struct jw w;
    jw_doc_begin(&w, RUN_SCHEMA, s, "");
    jw_obj_end(&w); /* context */
    jw_kv_str(&w, "command", run->command);
    jw_kv_str(&w, "folder", run->folder);
    jw_kv_num(&w, "wall_seconds", run->wall_seconds);
    jw_kv_arr(&w, "steps");
    for (int i = 0; i < run->nsteps; i++) {
        const struct report_step *st = &run->steps[i];
        jw_obj_begin(&w);
        jw_kv_str(&w, "name", st->name);
        jw_kv_str(&w, "status", st->exit_code ? "failed" : "ok");
        if (st->exit_code) jw_kv_int(&w, "exit_code", st->exit_code);
        else jw_kv_str(&w, "message", st->message);
        jw_kv_num(&w, "seconds", st->seconds);
        jw_obj_end(&w);
    }
    jw_arr_end(&w);
    jw_kv_obj(&w, "parts");
    for (int p = 0; p < REPORT_PART_COUNT; p++) {
        const struct report_part_state *ps = &run->parts[p];
        if (!ps->ran) continue;
        jw_kv_obj(&w, part_names[p]);
        jw_kv_str(&w, "status", ps->missing[0] ? "missing" : "ok");
        if (ps->missing[0]) jw_kv_str(&w, "reason", ps->missing);
        jw_obj_end(&w);
    }
    jw_obj_end(&w);
    jw_kv_str(&w, "images_note", run->images_note ? run->images_note : "");
    jw_kv_arr(&w, "pictures");
    for (int i = 0; i < run->npictures; i++) {
        const struct report_picture *pic = &run->pictures[i];
        jw_obj_begin(&w);
        jw_kv_str(&w, "file", pic->file);
        jw_kv_str(&w, "section", section_names[pic->section]);
        jw_kv_str(&w, "caption", pic->caption);
        if (pic->not_drawn[0]) jw_kv_str(&w, "not_drawn", pic->not_drawn);
        jw_obj_end(&w);
    }
    jw_arr_end(&w);
    jw_obj_end(&w);
    char path[4200];
    if (path_join(path, sizeof path, run_dir, "run.json")) {
        jw_free(&w);
        snprintf(err, errlen, "%s/run.json: path too long", run_dir);
        return -1;
    }
    return jw_write_file_free(&w, path, err, errlen) ? -1 : 0;
}

/* ---- reading ------------------------------------------------------------------------- */

static int name_index(const char *const *names, int count, const char *name)
{
    for (int i = 0; i < count; i++)
        if (strcmp(names[i], name) == 0) return i;
    return -1;
}

static int read_context(struct report_run_doc *r, char *err, size_t errlen)
{
    const struct jr_doc *d = &r->doc;
    const struct jr_value *ctx;
    if (jr_need(d, &d->root, "context", JR_OBJ, &ctx, err, errlen) ||
        jr_need_str(d, ctx, "date", &r->date, err, errlen) ||
        jr_need_str(d, ctx, "git_revision", &r->git_revision, err, errlen) ||
        jr_need_str(d, ctx, "host_cpu", &r->host_cpu, err, errlen))
        return 2;
    /* a run without a device has no device block */
    const struct jr_value *dev = jr_get(ctx, "device"), *pv = jr_get(ctx, "platform_version");
    r->device = dev && dev->type == JR_STR ? dev->str : NULL;
    r->platform_version = pv && pv->type == JR_STR ? pv->str : "";
    return 0;
}

/* The array member `key` of run.json, each item checked by check. */
static int read_items(const struct jr_doc *d, const char *key, const struct jr_value **arr,
                      int (*check)(const struct jr_doc *, const struct jr_value *, char *, size_t), char *err,
                      size_t errlen)
{
    if (jr_need(d, &d->root, key, JR_ARR, arr, err, errlen)) return 2;
    for (size_t i = 0; i < (*arr)->count; i++)
        if (check(d, &(*arr)->items[i], err, errlen)) return 2;
    return 0;
}

static int check_step(const struct jr_doc *d, const struct jr_value *st, char *err, size_t errlen)
{
    const char *name, *status, *msg;
    double secs, code;
    if (jr_need_str(d, st, "name", &name, err, errlen) || jr_need_str(d, st, "status", &status, err, errlen) ||
        jr_need_num(d, st, "seconds", &secs, err, errlen))
        return 2;
    if (strcmp(status, "ok") == 0 ? jr_need_str(d, st, "message", &msg, err, errlen)
        : strcmp(status, "failed") == 0 ? jr_need_num(d, st, "exit_code", &code, err, errlen)
                                        : jr_fail(d, st, err, errlen, "step status must be \"ok\" or \"failed\""))
        return 2;
    if (!(secs >= 0 && secs <= 1e9))
        return jr_fail(d, st, err, errlen, "step \"seconds\" is %g (accepted: 0 to 1e9)", secs);
    if (strcmp(status, "failed") == 0 && !(code >= 1 && code <= 255 && code == (int)code))
        return jr_fail(d, st, err, errlen, "step \"exit_code\" is %g (accepted: a whole number from 1 to 255)", code);
    return 0;
}

static int read_parts(struct report_run_doc *r, char *err, size_t errlen)
{
    const struct jr_doc *d = &r->doc;
    const struct jr_value *parts;
    if (jr_need(d, &d->root, "parts", JR_OBJ, &parts, err, errlen)) return 2;
    for (size_t i = 0; i < parts->count; i++) {
        int p = name_index(part_names, REPORT_PART_COUNT, parts->keys[i]);
        const struct jr_value *v = &parts->items[i];
        const char *status, *reason = NULL;
        if (p < 0)
            return jr_fail(d, v, err, errlen, "unknown part \"%s\"", parts->keys[i]);
        if (v->type != JR_OBJ) return jr_fail(d, v, err, errlen, "part \"%s\" must be an object", parts->keys[i]);
        if (jr_need_str(d, v, "status", &status, err, errlen)) return 2;
        if (strcmp(status, "missing") == 0 && jr_need_str(d, v, "reason", &reason, err, errlen)) return 2;
        if (strcmp(status, "ok") != 0 && !reason)
            return jr_fail(d, v, err, errlen, "part status must be \"ok\" or \"missing\"");
        r->part_ran[p] = 1;
        r->part_missing[p] = reason;
    }
    return 0;
}

static int check_picture(const struct jr_doc *d, const struct jr_value *pic, char *err, size_t errlen)
{
    const char *file, *section, *caption;
    if (jr_need_str(d, pic, "file", &file, err, errlen) || jr_need_str(d, pic, "section", &section, err, errlen) ||
        jr_need_str(d, pic, "caption", &caption, err, errlen))
        return 2;
    if (name_index(section_names, REPORT_SECTION_COUNT, section) < 0)
        return jr_fail(d, pic, err, errlen, "unknown section \"%s\" (heatmaps, plots, throughput, images)", section);
    /* the pictures of the run folder's top level, named as plots.json names them */
    if (!plot_file_name_ok(file) || strlen(file) >= sizeof((struct report_picture *)0)->file) {
        char shown[128];   /* a control character is shown as '?': the message stays one line */
        size_t k = 0;
        for (; file[k] && k < sizeof shown - 1; k++) shown[k] = (unsigned char)file[k] < 0x20 ? '?' : file[k];
        shown[k] = '\0';
        return jr_fail(d, pic, err, errlen, "picture file \"%s\" (accepted: NAME.png, a plain file name of letters, "
                       "digits and ._-+=, not starting with '.', under %zu bytes)", shown,
                       sizeof((struct report_picture *)0)->file);
    }
    return 0;
}

int report_run_read(const char *run_dir, struct report_run_doc *r, char *err, size_t errlen)
{
    char path[4200];
    memset(r, 0, sizeof *r);
    if (path_join(path, sizeof path, run_dir, "run.json")) {
        snprintf(err, errlen, "%s/run.json: path too long", run_dir);
        return 2;
    }
    struct stat st;
    if (stat(path, &st) != 0 && errno == ENOENT) {
        snprintf(err, errlen, "%s: No such file: not a run folder of `brdfbench all` (which records its run there)",
                 path);
        return 2;
    }
    if (jr_parse_file(path, &r->doc, err, errlen)) return 2;
    const struct jr_doc *d = &r->doc;
    const char *schema;
    int rc = jr_need_str(d, &d->root, "schema", &schema, err, errlen);
    if (!rc && strcmp(schema, RUN_SCHEMA) != 0)
        rc = jr_fail(d, &d->root, err, errlen, "schema \"%s\" is not %s (the run record of `brdfbench all`)", schema,
                     RUN_SCHEMA);
    if (!rc)
        rc = jr_need_str(d, &d->root, "command", &r->command, err, errlen) ||
             jr_need_str(d, &d->root, "folder", &r->folder, err, errlen) ||
             jr_need_num(d, &d->root, "wall_seconds", &r->wall_seconds, err, errlen) ||
             jr_need_str(d, &d->root, "images_note", &r->images_note, err, errlen) || read_context(r, err, errlen) ||
             read_items(d, "steps", &r->steps, check_step, err, errlen) || read_parts(r, err, errlen) ||
             read_items(d, "pictures", &r->pictures, check_picture, err, errlen);
    if (rc) {
        jr_free(&r->doc);
        memset(r, 0, sizeof *r);
        return 2;
    }
    return 0;
}

int report_section_of(const char *name)
{
    return name_index(section_names, REPORT_SECTION_COUNT, name);
}

void report_run_free(struct report_run_doc *r)
{
    jr_free(&r->doc);
    memset(r, 0, sizeof *r);
}
