/* compare_check.c - the figures and labels of a result file that compare reads, checked before
 * any is read (compare_check.h). */
#include "compare_check.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

enum fig { FIG_NONE = 0, FIG_RATE, FIG_ERROR, FIG_SCORE };

/* What a member holds, by its name and its parent's: a rate (a *_per_s number, the min, median
   and max of a *_per_s object, a *_reps array of rates), an error, a PSNR, or no figure. */
static enum fig fig_of(const char *parent, const char *name)
{
    static const char *const stats[] = { "min", "median", "max" };
    if (strstr(name, "per_s") || strstr(name, "_reps"))
        return FIG_RATE;
    for (size_t i = 0; parent && i < sizeof stats / sizeof stats[0]; ++i)
        if (strcmp(name, stats[i]) == 0 && strstr(parent, "per_s"))
            return FIG_RATE;
    if (strcmp(name, "max_rel") == 0 || strcmp(name, "max_abs") == 0 || strcmp(name, "rmse") == 0 ||
        strcmp(name, "mean_abs") == 0 || strcmp(name, "max_abs_whole") == 0)
        return FIG_ERROR;
    if (strcmp(name, "psnr_db") == 0)
        return FIG_SCORE;
    return FIG_NONE;
}

/* The members whose text becomes a row's key or a table cell. */
static int is_label(const char *name)
{
    static const char *const labels[] = { "label", "model", "scene", "name", "variant", "n_mode", "device", "tag" };
    for (size_t i = 0; i < sizeof labels / sizeof labels[0]; ++i)
        if (strcmp(name, labels[i]) == 0)
            return 1;
    return 0;
}

static int check_number(const struct jr_doc *d, const struct jr_value *v, const char *name, enum fig f, char *err,
                        size_t errlen)
{
    static const char *const accepted[] = { "", "a rate in [0, 1e+18]", "an error in [0, 1e+100]",
                                            "a PSNR in [-1000, 1000] dB" };
    int ok = f == FIG_RATE    ? v->num >= 0 && v->num <= CMP_MAX_RATE
             : f == FIG_ERROR ? v->num >= 0 && v->num <= CMP_MAX_ERROR
                              : fabs(v->num) <= 1000;
    if (ok)
        return 0;
    snprintf(err, errlen, "%s:%d:%d: \"%s\" is %.6g (accepted: %s, or null when not measured)", d->name, v->line,
             v->col, name, v->num, accepted[f]);
    return 2;
}

static int check_value(const struct jr_doc *d, const struct jr_value *v, const char *parent, const char *name,
                       int depth, char *err, size_t errlen)
{
    if (depth > 64 || (name && strcmp(name, "definitions") == 0))
        return 0;   /* the definitions are words about the figures; nothing compare reads is this deep */
    enum fig f = name ? fig_of(parent, name) : FIG_NONE;
    /* a figure's place holds a number, a rate's also an object of min/median/max, a *_reps
       member an array */
    if ((v->type == JR_ARR && f != FIG_NONE && !strstr(name, "_reps")) ||
        (v->type == JR_OBJ && (f == FIG_ERROR || f == FIG_SCORE))) {
        snprintf(err, errlen, "%s:%d:%d: \"%s\" is not a number (accepted: a number, or null when not measured)",
                 d->name, v->line, v->col, name);
        return 2;
    }
    if (v->type == JR_OBJ || v->type == JR_ARR) {
        int is_reps = v->type == JR_ARR && f == FIG_RATE;
        for (size_t i = 0; i < v->count; ++i) {
            const struct jr_value *it = &v->items[i];
            if (is_reps && it->type != JR_NUM) {
                snprintf(err, errlen, "%s:%d:%d: \"%s\" holds a value that is not a number (accepted: rates in "
                         "[0, 1e+18])", d->name, it->line, it->col, name);
                return 2;
            }
            if (is_reps ? check_number(d, it, name, FIG_RATE, err, errlen)
                        : check_value(d, it, name, v->type == JR_OBJ ? v->keys[i] : NULL, depth + 1, err, errlen))
                return 2;
        }
        return 0;
    }
    if (f != FIG_NONE && v->type == JR_NUM)
        return check_number(d, v, name, f, err, errlen);
    if (f != FIG_NONE && v->type != JR_NULL && !(f == FIG_RATE && strstr(name, "_reps"))) {
        snprintf(err, errlen, "%s:%d:%d: \"%s\" is %s (accepted: a number, or null when not measured)", d->name,
                 v->line, v->col, name, v->type == JR_STR ? "a string" : v->type == JR_BOOL ? "a boolean" : "not a number");
        return 2;
    }
    if (name && v->type == JR_STR && is_label(name)) {
        for (const char *p = v->str; *p; ++p)
            if ((unsigned char)*p < 0x20 || *p == '|' || *p == 0x7f) {
                snprintf(err, errlen, "%s:%d:%d: \"%s\" holds %s (accepted: one line of text without '|', as "
                         "brdfbench writes it)", d->name, v->line, v->col, name,
                         *p == '\n' ? "a newline" : *p == '|' ? "'|', which would break the table" : "a control character");
                return 2;
            }
    }
    return 0;
}

int compare_check_doc(const struct jr_doc *d, char *err, size_t errlen)
{
    return check_value(d, &d->root, NULL, NULL, 0, err, errlen);
}
