/* rdoc_upgrade_energy.c - brdfbench.energy/1 as rows (rdoc_upgrade_energy.h). */
#include "rdoc_upgrade_energy.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* A section's "models" array (section.models), or NULL with err. */
static const struct jr_value *models_of(const struct jr_doc *j, const char *section, char *err, size_t errlen)
{
    const struct jr_value *sec, *models;
    if (jr_need(j, &j->root, section, JR_OBJ, &sec, err, errlen) || jr_need(j, sec, "models", JR_ARR, &models, err, errlen))
        return NULL;
    return models;
}

static double num_in(const struct jr_value *o, const char *obj, const char *key)
{
    return jr_num_or_nan(obj ? jr_get(o, obj) : o, key);
}

int upgrade_energy_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    const struct jr_value *albedo = models_of(j, "albedo", err, errlen);
    const struct jr_value *recip = albedo ? models_of(j, "reciprocity", err, errlen) : NULL;
    const struct jr_value *pass = recip ? models_of(j, "reciprocity_image_pass", err, errlen) : NULL;
    if (!pass)
        return 2;
    char text[RD_TEXT];
    snprintf(text, sizeof text, "%.17g", num_in(&j->root, "albedo", "tolerance"));
    rd_ctx_put(&d->ctx, "energy quadrature tolerance", text);
    snprintf(text, sizeof text, "%.0f", num_in(&j->root, "reciprocity", "pairs"));
    rd_ctx_put(&d->ctx, "energy reciprocity pairs", text);
    for (size_t i = 0; i < albedo->count; ++i) {
        const struct jr_value *m = &albedo->items[i];
        const char *model = jr_str_or(m, "model", "?");
        struct rd_row *r = rdoc_row(d, "", model);
        if (!r)
            return 0;
        rd_row_key(r, "check", NULL, "albedo");
        rd_row_key(r, "model", NULL, model);
        rd_row_key(r, "integrand", NULL, jr_str_or(m, "integrand", "?"));
        rd_row_metric(d, r, "max_albedo", "1", RD_NEITHER, 0, jr_num_or_nan(m, "max_albedo"));
        rd_row_metric(d, r, "max_at_n", "1", RD_NEITHER, 0, jr_num_or_nan(m, "max_at_n"));
        rd_row_metric(d, r, "max_at_theta_i_deg", "deg", RD_NEITHER, 0, jr_num_or_nan(m, "max_at_theta_i_deg"));
        rd_row_metric(d, r, "refine_change", "1", RD_LOWER, 0, jr_num_or_nan(m, "refine_change"));
        rd_row_metric(d, r, "normal_incidence_max_diff", "1", RD_LOWER, 0, jr_num_or_nan(m, "normal_incidence_max_diff"));
    }
    for (size_t i = 0; i < recip->count; ++i) {
        const struct jr_value *m = &recip->items[i];
        const char *model = jr_str_or(m, "model", "?");
        struct rd_row *r = rdoc_row(d, "", model);
        if (!r)
            return 0;
        rd_row_key(r, "check", NULL, "reciprocity");
        rd_row_key(r, "model", NULL, model);
        rd_row_attr(r, "lobe", jr_str_or(m, "lobe", "?"));
        rd_row_metric(d, r, "device.max_diff_of_peak", "1", RD_LOWER, 0, num_in(m, "device_worst", "max_diff_of_peak"));
        rd_row_metric(d, r, "device.at_n", "1", RD_NEITHER, 0, num_in(m, "device_worst", "n"));
        if (jr_get(jr_get(m, "device_worst"), "max_eval_error_of_peak"))
            rd_row_metric(d, r, "device.max_eval_error_of_peak", "1", RD_LOWER, 0,
                          num_in(m, "device_worst", "max_eval_error_of_peak"));
        rd_row_metric(d, r, "host.max_diff_of_peak", "1", RD_LOWER, 0, num_in(m, "host_worst", "max_diff_of_peak"));
    }
    for (size_t i = 0; i < pass->count; ++i) {
        const struct jr_value *m = &pass->items[i];
        const char *model = jr_str_or(m, "model", "?");
        struct rd_row *r = rdoc_row(d, "", model);
        if (!r)
            return 0;
        rd_row_key(r, "check", NULL, "reciprocity_image_pass");
        rd_row_key(r, "model", NULL, model);
        snprintf(text, sizeof text, "%.0f", jr_num_or_nan(m, "shading_mode"));
        rd_row_key(r, "shading_mode", "mode ", text);
        rd_row_metric(d, r, "device_max_rel_diff", "1", RD_LOWER, 0, jr_num_or_nan(m, "device_max_rel_diff"));
        rd_row_metric(d, r, "host_max_rel_diff", "1", RD_LOWER, 0, jr_num_or_nan(m, "host_max_rel_diff"));
        rd_row_metric(d, r, "pairs_lit_both_ways", "1", RD_NEITHER, 0, jr_num_or_nan(m, "pairs_lit_both_ways"));
    }
    return 0;
}
