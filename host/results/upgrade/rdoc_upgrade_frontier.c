/* rdoc_upgrade_frontier.c - the rows of a frontier.json written before brdfbench.frontier/3
 * (rdoc_upgrade_frontier.h). The layout of /1 and /2 is the same (/2 added a rows member with
 * the accuracy figures alone); every figure of frontier_rows is in it: the ranges' max_rel and
 * max_abs, psnr_db (with psnr_reason when it is no number), rate_uniform and rate_varying
 * (median, min, max), on_front, kind and source, the context's rounds and reps. */
#include "rdoc_upgrade_frontier.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "report_frontier.h"

/* A number member of obj's member sub (NaN when either is missing or null). */
static double num_in(const struct jr_value *obj, const char *sub, const char *key)
{
    const struct jr_value *o = obj ? jr_get(obj, sub) : NULL;
    return o && o->type == JR_OBJ ? jr_num_or_nan(o, key) : NAN;
}

/* A context count (rounds, reps) as frontier_rows writes it. */
static void ctx_count(struct rdoc *d, const struct jr_value *ctx, const char *key)
{
    double v = ctx ? jr_num_or_nan(ctx, key) : NAN;
    if (!isfinite(v))
        return;
    char buf[32];
    snprintf(buf, sizeof buf, "%d", (int)v);
    rd_ctx_put(&d->ctx, key, buf);
}

int upgrade_frontier_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    static const char *const ranges[2] = { "n_2_1000", "n_16_1000" };
    static const char *const rates[2][2] = { { "rate_uniform", FRONTIER_RATE_UNIFORM },
                                             { "rate_varying", FRONTIER_RATE_VARYING } };
    const struct jr_value *ctx = jr_get(&j->root, "context"), *models = jr_get(&j->root, "models");
    if (!models || models->type != JR_ARR)
        return jr_fail(j, &j->root, err, errlen, "no \"models\" array (accepted: frontier.json as brdfbench writes it)");
    ctx_count(d, ctx && ctx->type == JR_OBJ ? ctx : NULL, "rounds");
    ctx_count(d, ctx && ctx->type == JR_OBJ ? ctx : NULL, "reps");
    for (size_t i = 0; i < models->count; ++i) {
        const struct jr_value *m = &models->items[i];
        if (m->type != JR_OBJ)
            return jr_fail(j, m, err, errlen, "a model that is not an object");
        const char *model = jr_str_or(m, "model", NULL);
        if (!model)
            return jr_fail(j, m, err, errlen, "a model without \"model\"");
        struct rd_row *r = rdoc_row(d, jr_str_or(m, "device", ""), model);
        if (!r)
            return 0;   /* d->oom: the caller says so */
        r->line = m->line;
        rd_row_key(r, "model", NULL, model);
        const char *kind = jr_str_or(m, "kind", NULL);
        if (kind)
            rd_row_attr(r, "kind", kind);
        const char *status = jr_str_or(m, "status", "ok");
        if (strcmp(status, "ok") != 0)
            rd_row_fail(r, status, jr_str_or(m, "reason", status));
        for (int k = 0; k < 2; ++k) {
            char name[RD_NAME];
            snprintf(name, sizeof name, "%s.max_rel", ranges[k]);
            rd_row_metric(d, r, name, "1", RD_LOWER, 0, num_in(m, ranges[k], "max_rel"));
            snprintf(name, sizeof name, "%s.max_abs", ranges[k]);
            rd_row_metric(d, r, name, "1", RD_LOWER, 0, num_in(m, ranges[k], "max_abs"));
        }
        rd_row_metric(d, r, "psnr_db", "dB", RD_HIGHER, 0, jr_num_or_nan(m, "psnr_db"));
        for (int k = 0; k < 2; ++k) {
            struct rd_metric *rate = rd_row_metric(d, r, rates[k][1], "1/s", RD_NEITHER, 0,
                                                   num_in(m, rates[k][0], "median"));
            if (rate) {
                rate->lo = num_in(m, rates[k][0], "min");
                rate->hi = num_in(m, rates[k][0], "max");
            }
        }
        const struct jr_value *front = jr_get(m, "on_front");
        rd_row_metric(d, r, "on_front", "1", RD_NEITHER, 0, front && front->type == JR_BOOL && front->num ? 1.0 : 0.0);
        const char *source = jr_str_or(m, "source", NULL), *psnr_reason = jr_str_or(m, "psnr_reason", NULL);
        if (source)
            rd_row_text(d, r, "source", source);
        if (psnr_reason)
            rd_row_text(d, r, "psnr_reason", psnr_reason);
    }
    return 0;
}
