/* shaderlang.c - GLSL/HLSL-style model texts translated into the OpenCL C user-model form
 * (see shaderlang.h and docs/user-models.md, "Shader-language models").
 *
 * Three stages: a lexer (comments, object-like #define, numbers with their suffixes), a
 * recursive-descent parser to a small syntax tree, and an emitter that checks types while it
 * writes the C. The emitter writes straight-line code: every float value is REAL, a vector is
 * one REAL per component, a value that is used more than once is kept in a temporary, and
 * control flow becomes selection: an assignment under `if` is `x = mask ? new : x`, a return
 * under `if` sets the result and clears a "still running" mask. Integers and booleans that
 * depend only on literals and integers stay C ints (the same in every lane); a boolean that may
 * differ between lanes is kept as a REAL mask of 0 and 1, so that its type is REAL's in every
 * build. A failure anywhere longjmps to the entry point with its message. */
#define _POSIX_C_SOURCE 200809L
#include "shaderlang.h"
#include "shaderlang_internal.h"
#include "clsession.h"
#include "exitcodes.h"
#include "mdbuf.h"

#include <ctype.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the program ------------------------------------------------------------------------- */

/* Reads what the translation needs from a brdfbench-model header; usermodel.c checks it all. */
void sl_read_header(const char *text, size_t len, struct header *h)
{
    memset(h, 0, sizeof *h);
    size_t i = 0;
    while (i < len && isspace((unsigned char)text[i]))
        ++i;
    if (i + 2 > len || text[i] != '/' || text[i + 1] != '*')
        return;
    const char *start = text + i + 2;
    const char *close = NULL;
    for (const char *p = start; p + 1 < text + len; ++p)
        if (p[0] == '*' && p[1] == '/') {
            close = p;
            break;
        }
    if (!close)
        return;
    const char *p = start;
    int first = 1;
    int line = 1;
    for (size_t k = 0; k < i; ++k)
        line += text[k] == '\n';
    while (p < close) {
        const char *eol = memchr(p, '\n', (size_t)(close - p));
        if (!eol)
            eol = close;
        const char *a = p, *b = eol;
        while (a < b && isspace((unsigned char)*a))
            ++a;
        if (!first && a < b && *a == '*')
            ++a;
        while (a < b && isspace((unsigned char)*a))
            ++a;
        while (b > a && isspace((unsigned char)b[-1]))
            --b;
        if (first) {
            if ((size_t)(b - a) != 15 || strncmp(a, "brdfbench-model", 15) != 0)
                return;
            first = 0;
        } else {
            const char *colon = memchr(a, ':', (size_t)(b - a));
            if (colon) {
                const char *k = a, *ke = colon;
                while (ke > k && isspace((unsigned char)ke[-1]))
                    --ke;
                const char *v = colon + 1;
                while (v < b && isspace((unsigned char)*v))
                    ++v;
                const char *ve = v;
                while (ve < b && !isspace((unsigned char)*ve))
                    ++ve;
                size_t kl = (size_t)(ke - k), vl = (size_t)(ve - v);
                if (vl > SL_NAME_MAX)
                    vl = SL_NAME_MAX;
                if (kl == 4 && strncmp(k, "name", 4) == 0)
                    snprintf(h->name, sizeof h->name, "%.*s", (int)vl, v);
                else if (kl == 8 && strncmp(k, "function", 8) == 0)
                    snprintf(h->function, sizeof h->function, "%.*s", (int)vl, v);
                else if (kl == 9 && strncmp(k, "reference", 9) == 0)
                    snprintf(h->reference, sizeof h->reference, "%.*s", (int)vl, v);
                else if (kl == 4 && strncmp(k, "lobe", 4) == 0)
                    snprintf(h->lobe, sizeof h->lobe, "%.*s", (int)(vl < 15 ? vl : 15), v);
                else if (kl == 11 && strncmp(k, "description", 11) == 0)
                    snprintf(h->description, sizeof h->description, "%.*s", (int)(b - v), v);
                else if (kl == 6 && strncmp(k, "define", 6) == 0 && !h->define_error[0]) {
                    /* define: NAME[=VALUE] (the shader-language preprocessor's, shaderlang_pp.c) */
                    char arg[SL_DEFINE_MAX + 2];
                    snprintf(arg, sizeof arg, "%.*s", (int)(b - v), v);
                    h->define_line = line;
                    if (h->ndefines == SL_MAX_DEFINES)
                        snprintf(h->define_error, sizeof h->define_error, "more than %d define: lines",
                                 SL_MAX_DEFINES);
                    else if (sl_define_text(arg, h->defines[h->ndefines], sizeof h->defines[0], h->define_error,
                                            sizeof h->define_error, "define:") == 0)
                        h->ndefines++;
                }
                else if (kl == 5 && strncmp(k, "param", 5) == 0 && h->nparams < SL_MAX_PARAMS) {
                    snprintf(h->params[h->nparams], sizeof h->params[0], "%.*s", (int)vl, v);
                    const char *rest = ve;
                    h->integer[h->nparams] = 0;
                    for (const char *q = rest; q + 7 <= b; ++q)
                        if (strncmp(q, "integer", 7) == 0)
                            h->integer[h->nparams] = 1;
                    h->nparams++;
                }
            }
        }
        p = eol + 1;
        ++line;
    }
    h->present = 1;
    h->end = (size_t)(close + 2 - text);
}


int sl_valid_identifier(const char *s)
{
    if (!*s || !(isalpha((unsigned char)*s) || *s == '_') || strlen(s) > SL_NAME_MAX)
        return 0;
    for (const char *p = s; *p; ++p)
        if (!isalnum((unsigned char)*p) && *p != '_')
            return 0;
    return 1;
}

/* Translates text (the whole file or expression), whose model is called name. */
/* The luminance of a colour and the geometry of the lobe of a full BRDF: L = N, V at 2 theta_h
 * from N in the XZ plane (N.V = 2c^2 - 1, N.H = V.H = c), 0 where V is below the horizon, as the
 * built-in physical models (kernels/brdf_models.h, brdf_pb_lobe). */
#define SL_LOBE_GEOMETRY                                                                               \
    "vec3 brdfbench_N = vec3(0.0, 0.0, 1.0); "                                                         \
    "float brdfbench_nv = 2.0 * brdfbench_c * brdfbench_c - 1.0; "                                     \
    "vec3 brdfbench_V = vec3(2.0 * brdfbench_c * sqrt(max((1.0 - brdfbench_c) * (1.0 + brdfbench_c), 0.0)), " \
    "0.0, brdfbench_nv); "
#define SL_LUMINANCE "vec3(0.2126, 0.7152, 0.0722)"
/* The tangents X, Y a full BRDF of (L, V, N, X, Y) gets at a normal N of the scene: the
 * branch-free orthonormal basis of Duff et al. 2017 ("Building an orthonormal basis, revisited");
 * an isotropic BRDF does not depend on them. */
#define SL_TANGENT_FRAME                                                                               \
    "float brdfbench_s = brdfbench_N.z >= 0.0 ? 1.0 : -1.0; "                                          \
    "float brdfbench_a = -1.0 / (brdfbench_s + brdfbench_N.z); "                                       \
    "float brdfbench_b = brdfbench_N.x * brdfbench_N.y * brdfbench_a; "                                \
    "vec3 brdfbench_X = vec3(1.0 + brdfbench_s * brdfbench_N.x * brdfbench_N.x * brdfbench_a, "        \
    "brdfbench_s * brdfbench_b, -brdfbench_s * brdfbench_N.x); "                                       \
    "vec3 brdfbench_Y = vec3(brdfbench_b, brdfbench_s + brdfbench_N.y * brdfbench_N.y * brdfbench_a, " \
    "-brdfbench_N.y); "

/* The opening of the full-vector function of a full BRDF (SHADERLANG_FULL_FUNCTION), with nparams
 * model parameters, up to its first statement. */
void sl_full_function_open(struct md_buf *w, int nparams)
{
    md_printf(w, " float brdfbench_full(vec3 brdfbench_L, vec3 brdfbench_V, vec3 brdfbench_N, float brdfbench_n");
    for (int i = 0; i < nparams; ++i)
        md_printf(w, ", float brdfbench_p%d", i);
    md_printf(w, ") { " SL_TANGENT_FRAME);
}

/* A model function of vectors, float|vec3 f(vec3 L, vec3 V, vec3 N[, vec3 X, vec3 Y], float n
 * [, float p0[, float p1]]): a full BRDF. Appends and parses the lobe function that calls it
 * and returns that function. */
static struct func *full_brdf_lobe(struct sl *S, struct func *f, const struct header *h, struct stmt *globals)
{
    int nvec = 0;
    while (nvec < f->nparams && f->pty[nvec].b == B_FLOAT && f->pty[nvec].n == 3)
        ++nvec;
    static const char *form = "a full BRDF takes (vec3 L, vec3 V, vec3 N[, vec3 X, vec3 Y], float n[, float p0"
                              "[, float p1]]) and returns float or vec3";
    if (nvec != 3 && nvec != 5)
        FAIL(S, f->name, "%s (this one takes %d vectors first)", form, nvec);
    if (f->nparams <= nvec || f->pty[nvec].b != B_FLOAT || f->pty[nvec].n != 1)
        FAIL(S, f->name, "%s: the shininess n after the vectors is missing", form);
    for (int i = nvec + 1; i < f->nparams; ++i)
        if (f->pty[i].b != B_FLOAT || f->pty[i].n != 1)
            FAIL(S, f->pname[i], "%s", form);
    if (f->nparams - nvec - 1 != h->nparams)
        FAIL(S, f->name, "the full BRDF takes %d parameter%s after n, the header declares %d", f->nparams - nvec - 1,
             f->nparams - nvec - 1 == 1 ? "" : "s", h->nparams);
    if (!(f->ret.b == B_FLOAT && (f->ret.n == 1 || f->ret.n == 3)))
        FAIL(S, f->name, "%s (this one returns %s)", form, sl_type_name(S, f->ret));
    if (h->present && strcmp(h->lobe, "theta_h") != 0)
        FAIL(S, f->name, "a full BRDF is measured over theta_h: its header says 'lobe: theta_h'");
    struct md_buf w;
    md_init(&w);
    md_printf(&w, "float brdfbench_lobe(float brdfbench_c, float brdfbench_n");
    for (int i = 0; i < h->nparams; ++i)
        md_printf(&w, ", float brdfbench_p%d", i);
    md_printf(&w, ") { " SL_LOBE_GEOMETRY "%s brdfbench_r = %.*s(brdfbench_N, brdfbench_V, brdfbench_N, ",
              f->ret.n == 3 ? "vec3" : "float", f->name->len, f->name->p);
    if (nvec == 5)
        md_printf(&w, "vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0), ");
    md_printf(&w, "brdfbench_n");
    for (int i = 0; i < h->nparams; ++i)
        md_printf(&w, ", brdfbench_p%d", i);
    md_printf(&w, "); float brdfbench_y = %s; return brdfbench_nv > 0.0 ? brdfbench_y : 0.0; }",
              f->ret.n == 3 ? "dot(brdfbench_r, " SL_LUMINANCE ")" : "brdfbench_r");
    /* the same function at the vectors of a scene (render, the physical-cost table) */
    sl_full_function_open(&w, h->nparams);
    md_printf(&w, "%s brdfbench_r = %.*s(brdfbench_L, brdfbench_V, brdfbench_N, ", f->ret.n == 3 ? "vec3" : "float",
              f->name->len, f->name->p);
    if (nvec == 5)
        md_printf(&w, "brdfbench_X, brdfbench_Y, ");
    md_printf(&w, "brdfbench_n");
    for (int i = 0; i < h->nparams; ++i)
        md_printf(&w, ", brdfbench_p%d", i);
    md_printf(&w, "); return %s; }", f->ret.n == 3 ? "dot(brdfbench_r, " SL_LUMINANCE ")" : "brdfbench_r");
    if (w.failed) {
        md_free(&w);
        sl_fail_at(S, 0, 0, "out of memory");
    }
    /* the tokens go before the end of the text; the text is kept until the translation ends */
    char *kept = sl_arena_alloc(S, w.len + 1);
    memcpy(kept, w.s, w.len + 1);
    md_free(&w);
    struct tok eof = S->toks.v[--S->toks.n];
    S->pos = S->toks.n;
    sl_lex_span(S, kept, kept + strlen(kept), 0, 0, NULL);
    sl_tokv_push(S, &S->toks, eof);
    sl_parse_program(S, globals);
    for (struct func *g = S->funcs; g; g = g->next)
        if (sl_tok_is(g->name, "brdfbench_lobe"))
            return g;
    sl_fail_at(S, 0, 0, "internal: the lobe function of the full BRDF is missing");
}

/* Emits the function emit_name: the model's (c, n[, p...]), or with full set the full-vector
 * function of a full BRDF (REAL L, V, N components, n[, p...]). */
static void emit_function(struct sl *S, struct func *model, struct stmt *body, struct stmt *globals,
                          const struct header *h, const char *emit_name, int first_line, int full)
{
    S->line_next = -1;
    int fline = model && model->name->line > 0 ? model->name->line : first_line;
    S->stmt_line = fline;
    md_printf(&S->out, "#line %d \"", fline);
    for (const char *p = S->origin; *p; ++p) {
        if (*p == '"' || *p == '\\')
            md_append(&S->out, "\\", 1);
        md_append(&S->out, p, 1);
    }
    if (full)
        md_printf(&S->out, "\"\nREAL %s(REAL sl_a0_x, REAL sl_a0_y, REAL sl_a0_z, REAL sl_a1_x, REAL sl_a1_y, "
                  "REAL sl_a1_z, REAL sl_a2_x, REAL sl_a2_y, REAL sl_a2_z, REAL sl_n", emit_name);
    else
        md_printf(&S->out, "\"\nREAL %s(REAL sl_c, REAL sl_n", emit_name);
    for (int i = 0; i < h->nparams; ++i)
        md_printf(&S->out, ", RSCALAR sl_p%d", i);
    md_printf(&S->out, ")\n{\n");
    S->line_next = fline + 2;
    sl_push_scope(S, 1);
    S->globals = S->scope;
    struct fnctx fc = { .ret = { .b = B_FLOAT, .n = 1, .half = model && !full ? model->ret.half : 0 }, .is_model = 1 };
    S->fn = &fc;
    /* The arguments: in the function form in a scope of their own under the globals (a helper
       sees the globals, not the model's arguments); in the body form among the globals. */
    struct scope *args = S->globals;
    if (model) {
        sl_push_scope(S, 1);
        args = S->scope;
    }
    static const struct tok cn[2] = { { K_ID, 0, 0, "c", 1 }, { K_ID, 0, 0, "n", 1 } };
    struct tok pt[SL_MAX_PARAMS];
    if (full) {
        /* L, V, N, n, then the parameters */
        for (int i = 0; i < model->nparams; ++i) {
            struct sym *s = sl_declare(S, args, model->pname[i], model->pty[i]);
            int rh = model->pty[i].b == B_FLOAT && model->pty[i].half == 1;
            const char *o = rh ? "RHALF(" : "", *e = rh ? ")" : "";
            for (int k = 0; k < model->pty[i].n && i < 3; ++k)
                sl_out_line(S, "REAL %s = %ssl_a%d_%c%s;", s->c[k], o, i, "xyz"[k], e);
            if (i == 3)
                sl_out_line(S, "REAL %s = %ssl_n%s;", s->c[0], o, e);
            else if (i > 3)
                sl_out_line(S, "REAL %s = %sRSPLAT(sl_p%d)%s;", s->c[0], o, i - 4, e);
        }
    }
    for (int i = 0; i < 2 + h->nparams && !full; ++i) {
        const struct tok *pn;
        struct type ty = { .b = B_FLOAT, .n = 1 };
        if (model) {
            pn = model->pname[i];
            ty = model->pty[i];
        } else if (i < 2) {
            pn = &cn[i];
        } else {
            pt[i - 2] = (struct tok){ K_ID, 0, 0, h->params[i - 2], (int)strlen(h->params[i - 2]) };
            pn = &pt[i - 2];
            ty.b = h->integer[i - 2] ? B_INT : B_FLOAT;
        }
        struct sym *s = sl_declare(S, args, pn, ty);
        /* a half argument arrives in binary16 */
        int rh = ty.b == B_FLOAT && ty.half == 1;
        if (i < 2)
            sl_out_line(S, "REAL %s = %ssl_%c%s;", s->c[0], rh ? "RHALF(" : "", i == 0 ? 'c' : 'n', rh ? ")" : "");
        else if (ty.b == B_INT)
            sl_out_line(S, "int %s = (int)sl_p%d;", s->c[0], i - 2);
        else
            sl_out_line(S, "REAL %s = %sRSPLAT(sl_p%d)%s;", s->c[0], rh ? "RHALF(" : "", i - 2, rh ? ")" : "");
    }
    if (model) {
        S->scope = S->globals;
        sl_emit_block(S, globals, NULL, 0);
        S->scope = args;
        S->inlining[S->ninline++] = model;
        sl_emit_block(S, model->body, NULL, 0);
    } else {
        S->allow_implicit = 1;
        sl_emit_block(S, body, NULL, 0);
    }
    if (!fc.returned)
        sl_out_line(S, "return sl_ret;");
    md_printf(&S->out, "}\n");
}

/* The header as written, less its define: lines (the preprocessor's, not usermodel.c's keys),
 * each left as an empty line of the comment so that the lines keep their numbers. */
static void append_header(struct sl *S, const char *text, size_t n)
{
    for (size_t i = 0; i < n;) {
        const char *eol = memchr(text + i, '\n', n - i);
        size_t e = eol ? (size_t)(eol - text) + 1 : n;
        size_t k = i;
        while (k < e && (isspace((unsigned char)text[k]) || text[k] == '*'))
            ++k;
        size_t w = k;
        while (k < e && isalpha((unsigned char)text[k]))
            ++k;
        size_t wl = k - w;
        while (k < e && (text[k] == ' ' || text[k] == '\t'))
            ++k;
        if (wl == 6 && strncmp(text + w, "define", 6) == 0 && k < e && text[k] == ':') {
            int closes = 0;
            for (size_t q = i; q + 1 < e; ++q)
                if (text[q] == '*' && text[q + 1] == '/')
                    closes = 1;
            md_printf(&S->out, closes ? " */" : " *");
            if (eol && e <= n)
                md_append(&S->out, "\n", 1);
        } else {
            md_append(&S->out, text + i, e - i);
        }
        i = e;
    }
}

static __attribute__((noinline)) void translate_text(struct sl *S, const char *text, size_t len, const struct header *h, const char *name)
{
    S->src = text;
    if (h->define_error[0])
        sl_fail_at(S, h->define_line, -1, "%s", h->define_error);
    int first_line = h->first_line > 0 ? h->first_line : 1;
    if (h->prelude)
        sl_lex_span(S, h->prelude, h->prelude + strlen(h->prelude), 0, 0, NULL);
    size_t pp_len = 0;
    const char *pp = sl_preprocess(S, text, len, first_line, h, &pp_len);
    if (pp) {
        S->pp_active = 1;
        sl_lex_span(S, pp, pp + pp_len, first_line, 1, NULL);
        S->pp_active = 0;
    } else {
        sl_lex_span(S, text, text + len, first_line, 1, NULL);
    }
    if (h->epilogue)
        sl_lex_span(S, h->epilogue, h->epilogue + strlen(h->epilogue), 0, 0, NULL);
    sl_tokv_push(S, &S->toks, (struct tok){ K_EOF, 0, 0, text + len, 0 });
    {
        /* the end-of-text token points after the last character */
        int line = first_line, col = 1;
        for (size_t i = 0; i < len; ++i) {
            if (text[i] == '\n') {
                ++line;
                col = 1;
            } else {
                ++col;
            }
        }
        S->toks.v[S->toks.n - 1].line = line;
        S->toks.v[S->toks.n - 1].col = col;
    }
    if (S->toks.n == 1)
        sl_fail_at(S, 0, 0, "the model has no code (a function of c and n, or statements ending in return)");
    struct stmt *globals = sl_new_stmt(S, S_BLOCK, sl_peek(S));
    globals->op = 1;
    struct stmt *body = sl_parse_program(S, globals);
    /* a file of functions (not a body, not a .brdf file's shader) is checked by the reference
       compiler first: its error is the one the engine's compiler would print */
    if (!body && !h->header_text)
        sl_validate(S, text, len, first_line, h);

    const char *fname = h->function[0] ? h->function : name;
    struct func *model = NULL;
    int full_brdf = 0;
    if (!body) {
        for (struct func *f = S->funcs; f; f = f->next)
            if ((int)strlen(fname) == f->name->len && strncmp(f->name->p, fname, (size_t)f->name->len) == 0)
                model = f;
        if (!model && h->function[0])
            sl_fail_at(S, 0, 0, "the header names the function '%s', which the text does not define", fname);
        if (!model)
            for (struct func *f = S->funcs; f; f = f->next)
                model = f; /* the last one */
        if (!model)
            sl_fail_at(S, 0, 0, "no function defined");
        if (model->nparams > 0 && model->pty[0].b == B_FLOAT && model->pty[0].n == 3) {
            model = full_brdf_lobe(S, model, h, globals);
            full_brdf = 1;
        }
        if (model->ret.b != B_FLOAT || model->ret.n != 1)
            FAIL(S, model->name, "the model's function must return float (a lobe value), not %s", sl_type_name(S, model->ret));
        if (model->nparams < 2)
            FAIL(S, model->name, "the model's function takes the cosine c and the shininess n first: "
                                 "float %.*s(float c, float n%s)", model->name->len, model->name->p,
                 h->nparams ? ", float ..." : "");
        for (int i = 0; i < model->nparams; ++i) {
            int want_int = i >= 2 && h->integer[i - 2];
            if (!(model->pty[i].b == B_FLOAT && model->pty[i].n == 1) && !(want_int && model->pty[i].b == B_INT))
                FAIL(S, model->pname[i], "parameter %d of the model's function is a %s; it takes floats "
                     "(c, n, then the header's parameters)", i + 1, sl_type_name(S, model->pty[i]));
        }
        if (model->nparams - 2 != h->nparams) {
            if (!h->present)
                FAIL(S, model->pname[2], "the model's parameter '%.*s' needs a range: begin the file with a header "
                     "/* brdfbench-model  name: %s  param: %.*s MIN MAX DEFAULT */ (docs/user-models.md)",
                     model->pname[2]->len, model->pname[2]->p, name, model->pname[2]->len, model->pname[2]->p);
            FAIL(S, model->name, "the model's function takes %d parameter%s after c and n, the header declares %d",
                 model->nparams - 2, model->nparams - 2 == 1 ? "" : "s", h->nparams);
        }
        if (!sl_stmt_returns(model->body))
            FAIL(S, model->close, "the function can reach its end without returning a value");
    } else if (!sl_stmt_returns(body)) {
        sl_fail_at(S, S->toks.v[S->toks.n - 1].line, S->toks.v[S->toks.n - 1].col,
                   "the model ends without returning a value (end it with return EXPR; or with an expression)");
    }
    if (h->function[0] && (strncmp(fname, "u__", 3) == 0 || strncmp(fname, "sl_", 3) == 0))
        sl_fail_at(S, 0, 0, "names beginning with u__ or sl_ are reserved in a shader-language model");

    /* The model function, in the form usermodel.c wraps. Unless the header names it, it is
       called sl_NAME (NAME: the shader's function, or "model"), so that a model's name never
       meets a word of OpenCL C (a model called half, or mix). */
    const char *emit_name = h->function[0] ? h->function
                            : model ? sl_sfmt(S, "sl_%.*s", model->name->len, model->name->p) : "sl_model";
    if (h->header_text) {
        md_printf(&S->out, "%s", h->header_text);
    } else if (h->present) {
        size_t close = h->end - 2, line_start = close;
        while (line_start > 0 && text[line_start - 1] != '\n')
            --line_start;
        int bare = line_start > 0;
        for (size_t i = line_start; i < close; ++i)
            if (!isspace((unsigned char)text[i]) && text[i] != '*')
                bare = 0;
        if (h->function[0]) {
            append_header(S, text, h->end);
        } else if (bare) {
            /* "function: ..." on the closing line, so the header keeps its lines */
            append_header(S, text, line_start);
            md_printf(&S->out, " * function: %s */", emit_name);
        } else {
            append_header(S, text, h->end);
            emit_name = name;
        }
        md_append(&S->out, "\n", 1);
    } else {
        md_printf(&S->out, "/* brdfbench-model\n * name: %s\n * function: %s\n%s */\n", name, emit_name,
                  full_brdf ? " * lobe: theta_h\n * reference: blinn\n * description: a full BRDF: luminance of "
                              "f(L = N, V) with theta_h = acos(c)\n" : "");
    }
    emit_function(S, model, body, globals, h, emit_name, first_line, 0);
    /* a full BRDF: its function of the vectors too */
    if (full_brdf || h->header_text)
        for (struct func *g = S->funcs; g; g = g->next)
            if (sl_tok_is(g->name, "brdfbench_full")) {
                S->scope = NULL;
                S->ninline = 0;
                emit_function(S, g, NULL, globals, h, SHADERLANG_FULL_FUNCTION, first_line, 1);
            }
    if (S->out.failed)
        sl_fail_at(S, 0, 0, "out of memory");
}

int sl_translate(struct sl *S, const char *text, size_t len, const struct header *h, const char *name,
                 char **out, size_t *outlen)
{
    md_init(&S->out);
    S->started = wall_seconds();
    S->fail_code = EXIT_USAGE;
    if (setjmp(S->fail)) {
        md_free(&S->out);
        return S->fail_code;
    }
    translate_text(S, text, len, h, name);
    *out = S->out.s;
    *outlen = S->out.len;
    return 0;
}

/* Translation is bounded (SL_MAX_UNROLL_TOTAL, SL_MAX_OUTPUT), and the launch deadline covers
 * it all the same: a text that takes longer than a launch may is stopped as a launch would be. */
void sl_check_deadline(struct sl *S)
{
    double limit = clsession_timeout();
    if (limit > 0 && wall_seconds() - S->started > limit) {
        S->fail_code = EXIT_RUNTIME;
        sl_fail_at(S, S->stmt_line, -1, "the translation took longer than the deadline of %g s (--timeout)", limit);
    }
}

void sl_free(struct sl *S)
{
    while (S->arena) {
        struct arena_block *b = S->arena;
        S->arena = b->next;
        free(b);
    }
}

int sl_uses_word(const char *text, size_t len, const char *w)
{
    size_t wl = strlen(w);
    for (size_t i = 0; i + wl <= len; ++i)
        if (strncmp(text + i, w, wl) == 0 && (i == 0 || !(isalnum((unsigned char)text[i - 1]) || text[i - 1] == '_')) &&
            (i + wl == len || !(isalnum((unsigned char)text[i + wl]) || text[i + wl] == '_')))
            return 1;
    return 0;
}
