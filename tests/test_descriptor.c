/* test_descriptor.c - every row of kernels/brdf_model_list.h is complete, and what the program
 * derives from the rows covers every model: ids in the enum's order, every field set, families
 * and kinds in range, references that exist, a colour of the palette, the operation counts of
 * every counted model; the tuned-C baseline (throughput's C column and the sweep's C timing)
 * takes every built-in model; the frontier's default set is the list docs/frontier.md gives,
 * written here a second time. A row with a field left out (or a model added past the enum's
 * end, which once lost its C column) fails here. No device is needed. */
#include "check.h"
#include "frontier.h"
#include "hostc_baseline.h"
#include "models.h"
#include "plots.h"

#include <stdio.h>
#include <string.h>

#define REAL double
#define RSCALAR double
#include "brdf_models.h"

static void every_field(void)
{
    CHECK(models_count() == BRDF_USER, "%d rows for %d built-in ids", models_count(), (int)BRDF_USER);
    for (int i = 0; i < models_count(); ++i) {
        const struct model_info *m = models_at(i);
        const char *id = m->id ? m->id : "(no id)";
        CHECK_CASE(id);
        CHECK(m->id && m->id[0], "row %d has an id", i);
        CHECK(m->kernel_id == i, "%s: kernel id %d is its row %d", id, m->kernel_id, i);
        CHECK(m->family >= 0 && m->family < MODEL_FAMILY_COUNT && m->family != MODEL_FAMILY_USER,
              "%s: family %d", id, (int)m->family);
        CHECK(strcmp(model_family_name(m->family), "?") != 0, "%s: family has a name", id);
        CHECK(m->lobe == LOBE_PSI || m->lobe == LOBE_THETA_H, "%s: lobe variable", id);
        CHECK(m->reference_id && models_find(m->reference_id) && model_is_builtin(models_find(m->reference_id)),
              "%s: reference '%s' is a built-in model", id, m->reference_id ? m->reference_id : "(none)");
        CHECK(m->formula && m->formula[0], "%s: formula in words", id);
        CHECK(m->description && m->description[0], "%s: description", id);
        CHECK(m->in_default_set == 0 || m->in_default_set == 1, "%s: in_default_set is 0 or 1", id);
        CHECK(m->kind >= 0 && m->kind < MODEL_KIND_COUNT, "%s: kind %d", id, (int)m->kind);
        CHECK(m->colour && plot_colour_known(m->colour), "%s: colour '%s' is a palette name", id,
              m->colour ? m->colour : "(none)");
        /* a model that is its own reference is drawn black, as every reference curve is */
        if (m->reference_id && strcmp(m->reference_id, m->id) == 0)
            CHECK(m->colour && strcmp(m->colour, "black") == 0, "%s: a reference is black", id);
        CHECK(m->ops.note && m->ops.note[0], "%s: the operation count says what it counts", id);
        if (m->ops.known)
            CHECK(m->ops.arith + m->ops.transc > 0, "%s: a counted formula has operations", id);
        CHECK(m->nparams >= 0 && m->nparams <= MODEL_MAX_PARAMS, "%s: nparams", id);
        for (int p = 0; p < m->nparams; ++p)
            CHECK(m->params[p].name && m->params[p].meaning && m->params[p].min <= m->params[p].def &&
                      m->params[p].def <= m->params[p].max,
                  "%s: parameter %d named, explained, default within its range", id, p);
        for (int j = 0; j < i; ++j)
            CHECK(strcmp(models_at(j)->id, id) != 0, "%s: id used once", id);
        /* the throughput's C column and the sweep's C timing take every built-in model */
        CHECK(hostc_supports(m->kernel_id), "%s: the tuned C baseline takes it", id);
    }
    CHECK_CASE("user model");
    CHECK(!hostc_supports(BRDF_USER), "the tuned C baseline refuses a user model (device only)");
}

/* The frontier's default set as docs/frontier.md lists it, in its order. */
static void frontier_set(void)
{
    CHECK_CASE("frontier default set");
    static const char *const want[] = { "phong", "phongpow", "cq2", "fvol", "fvol64", "schlick", "lyon", "fq",
                                        "fq2", "sg", "ue4phong", "bg", "bg:j=2", "kb", "kbswap", "bitpow",
                                        "gaussfit", "pow3fit", "pow4fit" };
    struct model_spec got[64];
    int n = frontier_default_models(got, 64);
    CHECK(n == (int)(sizeof want / sizeof want[0]), "frontier default set: %d models", n);
    for (int i = 0; i < n && i < (int)(sizeof want / sizeof want[0]); ++i) {
        struct model_spec w;
        char err[256];
        CHECK(model_spec_parse(want[i], &w, err, sizeof err) == 0, "%s parses", want[i]);
        CHECK(strcmp(got[i].label, w.label) == 0, "frontier default %d: %s (want %s)", i, got[i].label, w.label);
    }
}

/* Which models see only c: phongpow (pow(c, n) itself) and a user model; the rest take s. */
static void sees_only_c(void)
{
    CHECK_CASE("sees only c");
    for (int i = 0; i < models_count(); ++i) {
        const struct model_info *m = models_at(i);
        int want = strcmp(m->id, "phongpow") == 0;
        CHECK(brdf_sees_only_c(m->kernel_id) == want, "%s: sees only c = %d", m->id, want);
    }
    CHECK(brdf_sees_only_c(BRDF_USER) == 1, "a user model sees only c");
}

/* Kinds as docs/frontier.md groups the default set. */
static void kinds(void)
{
    CHECK_CASE("kinds");
    static const struct { const char *id; enum model_kind kind; } want[] = {
        { "phong", MODEL_KIND_REFERENCE }, { "phongpow", MODEL_KIND_REFERENCE }, { "fq2", MODEL_KIND_PAPER },
        { "schlick", MODEL_KIND_PAPER },   { "sg", MODEL_KIND_ENGINE },          { "bitpow", MODEL_KIND_ENGINE },
        { "pow3fit", MODEL_KIND_TUNED },   { "quad", MODEL_KIND_TUNED },         { "ct-ggx", MODEL_KIND_OTHER },
    };
    for (size_t i = 0; i < sizeof want / sizeof want[0]; ++i) {
        const struct model_info *m = models_find(want[i].id);
        CHECK(m && m->kind == want[i].kind, "%s: kind %s", want[i].id, model_kind_name(want[i].kind));
    }
}

int main(void)
{
    every_field();
    frontier_set();
    sees_only_c();
    kinds();
    return check_summary();
}
