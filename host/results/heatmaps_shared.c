/* heatmaps_shared.c - the run's heatmaps on one colour scale (heatmaps_shared.h). */
#define _POSIX_C_SOURCE 200809L
#include "heatmaps_shared.h"

#include "draw.h"
#include "exitcodes.h"
#include "field_report.h"
#include "outdir.h"
#include "plots.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SHARED_MAX_MODELS 200

static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

static int is_field_file(const char *name)
{
    size_t n = strlen(name);
    return n > strlen("field_.json") && strncmp(name, "field_", 6) == 0 && strcmp(name + n - 5, ".json") == 0;
}

char **field_file_names(const char *dir, size_t *count)
{
    *count = 0;
    DIR *d = opendir(dir);
    if (!d)
        return NULL;
    char **names = NULL;
    size_t cap = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (!is_field_file(e->d_name)) continue;
        if (*count == cap) {
            cap = cap ? cap * 2 : 32;
            char **nn = realloc(names, cap * sizeof *nn);
            if (!nn) break;
            names = nn;
        }
        if (!(names[*count] = strdup(e->d_name))) break;
        ++*count;
    }
    closedir(d);
    if (names)
        qsort(names, *count, sizeof *names, cmp_str);
    return names;
}

static double finite_max(const float *v, size_t n)
{
    double m = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(v[i]) && v[i] > m) m = v[i];
    return m;
}

/* The page: per model its delta and Delta panels, two models to a row. */
static int draw_page(const char *run_dir, const struct field_result *fr, int n, double epi, double att, char *err,
                     size_t errlen)
{
    struct draw_heatmap_panel *p = calloc((size_t)2 * n, sizeof *p);
    struct field_panel_text *t = calloc((size_t)n, sizeof *t);
    char (*sub)[2][200] = calloc((size_t)n, sizeof *sub);
    int rc = EXIT_RUNTIME;
    if (!p || !t || !sub) {
        snprintf(err, errlen, "%s: out of memory", HEATMAPS_SHARED_FILE);
        goto done;
    }
    for (int m = 0; m < n; m++) {
        field_heatmap_panels(&fr[m], epi, att, p + 2 * m, &t[m]);
        snprintf(sub[m][0], sizeof sub[m][0], "%s: delta (epicentre)", fr[m].model.label);
        snprintf(sub[m][1], sizeof sub[m][1], "%s: Delta (attenuation)", fr[m].model.label);
        for (int k = 0; k < 2; k++) {
            p[2 * m + k].subtitle = sub[m][k];
            p[2 * m + k].x_label = k == 0 ? "x / x_e(n)" : "x / x_e(n) (log)";
            p[2 * m + k].bar_label = k == 0 ? "delta (shared scale)" : "Delta (shared scale)";
        }
    }
    char path[4200], title[400];
    snprintf(title, sizeof title,
             "Every model's error fields on one scale per kind: delta in [0, %.4g%%], Delta in [0, %.4g]\n"
             "(the largest over the %d models; rows of n log-spaced, x normalised by x_e(n))", 100 * epi, att, n);
    if (path_join(path, sizeof path, run_dir, HEATMAPS_SHARED_FILE)) {
        snprintf(err, errlen, "%s/%s: path too long", run_dir, HEATMAPS_SHARED_FILE);
        goto done;
    }
    if (draw_heatmap_grid(path, title, 2 * n, n > 1 ? 4 : 2, p, err, errlen) == 0 &&
        plots_stamp_if_quick(path, 0, err, errlen) == 0)
        rc = 0;
done:
    free(p);
    free(t);
    free(sub);
    return rc;
}

/* Each model's own heatmap on the shared scales (only_label: that one). */
static int redraw_scaled(const char *run_dir, const struct field_result *fr, int n, double epi, double att,
                         const char *only_label, int *drawn, char *err, size_t errlen)
{
    for (int m = 0; m < n; m++) {
        if (only_label && strcmp(only_label, fr[m].model.label) != 0) continue;
        char safe[96], name[160], path[4300];
        field_safe_label(fr[m].model.label, safe, sizeof safe);
        snprintf(name, sizeof name, "heatmap_%s.png", safe);
        if (path_join(path, sizeof path, run_dir, name)) {
            snprintf(err, errlen, "%s/%s: path too long", run_dir, name);
            return EXIT_RUNTIME;
        }
        if (field_draw_heatmap_scaled(path, &fr[m], epi, att, NULL, err, errlen)) return EXIT_RUNTIME;
        if (drawn) ++*drawn;
    }
    return 0;
}

int plots_heatmaps_shared(const char *run_dir, int shared, const char *only_label, int *drawn, char *err,
                          size_t errlen)
{
    size_t count = 0;
    char **names = field_file_names(run_dir, &count);
    struct field_result *fr = calloc(count ? count : 1, sizeof *fr);
    int n = 0, rc = fr ? 0 : EXIT_RUNTIME;
    double epi = 0, att = 0;
    if (!fr) snprintf(err, errlen, "%s: out of memory", run_dir);
    for (size_t i = 0; i < count && !rc && n < SHARED_MAX_MODELS; i++) {
        char path[4300];
        if (path_join(path, sizeof path, run_dir, names[i]) || field_read_json(path, &fr[n], err, errlen)) {
            rc = EXIT_USAGE;
            break;
        }
        size_t cells = (size_t)fr[n].grid.rows * fr[n].grid.cols;
        epi = fmax(epi, finite_max(fr[n].epi_rel, cells));
        att = fmax(att, finite_max(fr[n].att_abs, cells));
        n++;
    }
    /* a scale of 0 (every field zero) would mean "the panel's own": the same [0, 1] as its own */
    if (!rc && n > 0 && shared) rc = redraw_scaled(run_dir, fr, n, epi > 0 ? epi : 1, att > 0 ? att : 1, only_label,
                                                   drawn, err, errlen);
    if (!rc && n > 0) rc = draw_page(run_dir, fr, n, epi > 0 ? epi : 1, att > 0 ? att : 1, err, errlen);
    for (int m = 0; m < n; m++) field_result_free(&fr[m]);
    for (size_t i = 0; i < count; i++) free(names[i]);
    free(names);
    free(fr);
    return rc;
}

int plots_heatmaps_shared_step(const char *cmd, const char *run_dir, int shared)
{
    char err[1024];
    int rc = plots_heatmaps_shared(run_dir, shared, NULL, NULL, err, sizeof err);
    if (rc)
        fprintf(stderr, "brdfbench %s: %s\n", cmd, err);
    return rc;
}
