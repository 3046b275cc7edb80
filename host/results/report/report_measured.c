/* report_measured.c - the "Measured materials" page from measured.json's rows (report_measured.h). */
#include "report_measured.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void report_measured_file_name(const char *name, char *out, size_t len)
{
    size_t i = 0;
    for (; name[i] && i + 1 < len; ++i) {
        char c = name[i];
        int keep = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' ||
                   c == '_' || c == '-';
        out[i] = keep ? c : '_';
    }
    out[i] = '\0';
}

void report_measured_stem(const char *name, const char *const *taken, int count, char *out, size_t len)
{
    char base[256];
    report_measured_file_name(name, base, sizeof base);
    snprintf(out, len, "%s", base);
    for (int k = 2;; ++k) {
        int used = 0;
        for (int j = 0; j < count && !used; ++j)
            used = strcmp(taken[j], out) == 0;
        if (!used)
            return;
        snprintf(out, len, "%s-%d", base, k);
    }
}

/* The row of `material` whose key `key` is `value` (NULL: the material's own row, which has
   neither a fit nor a lobe key). */
static const struct rd_row *row_of(const struct rdoc *d, const char *material, const char *key, const char *value)
{
    for (int i = 0; i < d->nrows; ++i) {
        const struct rd_row *r = &d->rows[i];
        const char *mat = rd_row_key_value(r, "material");
        if (!mat || strcmp(mat, material) != 0)
            continue;
        const char *fit = rd_row_key_value(r, MEASURED_FIT_KEY), *lobe = rd_row_key_value(r, MEASURED_LOBE_KEY);
        if (!key ? !fit && !lobe : (fit = rd_row_key_value(r, key)) != NULL && strcmp(fit, value) == 0)
            return r;
    }
    return NULL;
}

/* A metric of a row that may be missing (NaN then); a NaN of either sign as NAN, as the file
   gives it back (null), so that the page made from the rows in memory is the report's. */
static double value(const struct rd_row *r, const char *name)
{
    double v = r ? rd_row_value(r, name) : NAN;
    return isnan(v) ? NAN : v;
}

static void material(struct md_buf *b, const struct rdoc *d, const struct rd_row *m, const char *stem)
{
    const struct rd_row *bp = row_of(d, stem, MEASURED_FIT_KEY, "blinn-phong");
    const struct rd_row *ct[2] = { row_of(d, stem, MEASURED_FIT_KEY, "ct-beckmann"),
                                   row_of(d, stem, MEASURED_FIT_KEY, "ct-ggx") };
    const char *check = rd_row_text_or(m, "device_check", "not run");
    md_printf(b, "### ");
    md_text(b, rd_row_text_or(m, "name", stem));   /* a file's name: no markdown or HTML of its own */
    md_printf(b, "\n\n%ld cells used (%ld unmeasured, %ld below the surface); device lookup %s.\n\n",
              (long)value(m, "used_cells"), (long)value(m, "unmeasured_cells"), (long)value(m, "below_horizon_cells"),
              strcmp(check, "not run") == 0 ? "not run" : strcmp(check, "ok") == 0 ? "ok at every cell" : "**disagrees**");
    md_printf(b, "| fit | parameters | RMS error |\n|---|---|---|\n");
    md_printf(b, "| blinn-phong | n = %.5g, ks = %.5g, kd = %.5g | %.4g |\n", value(bp, "n"), value(bp, "ks"),
              value(bp, "kd"), value(bp, "rms"));
    for (int k = 0; k < 2; ++k)
        md_printf(b, "| %s | alpha = %.5g, F0 = %.4g, ks = %.5g, kd = %.5g | %.4g |\n%s",
                  k ? "ct-ggx" : "ct-beckmann", value(ct[k], "alpha"), value(ct[k], "F0"), value(ct[k], "ks"),
                  value(ct[k], "kd"), value(ct[k], "rms"), k ? "\n" : "");
    md_printf(b, "| lobe | error vs material | error vs Blinn-Phong | ratio |\n|---|---|---|---|\n");
    for (int i = 0; i < d->nrows; ++i) {
        const struct rd_row *r = &d->rows[i];
        const char *mat = rd_row_key_value(r, "material"), *lobe = rd_row_key_value(r, MEASURED_LOBE_KEY);
        if (mat && lobe && strcmp(mat, stem) == 0)
            md_printf(b, "| %s | %.5g | %.5g | %.4g |\n", lobe, value(r, "err_measured"), value(r, "err_phong"),
                      value(r, "ratio"));
    }
    md_printf(b, "\n![%s: each lobe's error against the material and against Blinn-Phong](measured_errors_%s.png)"
                 "\n\n![%s: the measured slice with the fitted curves](measured_slice_%s.png)\n\n",
              stem, stem, stem, stem);
}

int report_measured_page(struct md_buf *b, const struct rdoc *d)
{
    md_printf(b, "Each material's Blinn-Phong fit `ks cos(theta_h)^n + kd` and Cook-Torrance fits (alpha, F0, ks, "
                 "kd), by least squares on luminance in r = ln(1 + cos(theta_i) f) - ln(1 + cos(theta_i) Y) over its "
                 "measured cells; then every cheap lobe at the fitted n, scaled the same way: its RMS error against "
                 "the material, against the fitted Blinn-Phong, and the ratio (docs/measured.md; data in "
                 "`measured.json`).\n\n");
    for (int i = 0; i < d->nrows; ++i) {
        const struct rd_row *r = &d->rows[i];
        const char *stem = rd_row_key_value(r, "material");
        if (stem && !rd_row_key_value(r, MEASURED_FIT_KEY) && !rd_row_key_value(r, MEASURED_LOBE_KEY))
            material(b, d, r, stem);
    }
    return b->failed ? -1 : 0;
}
