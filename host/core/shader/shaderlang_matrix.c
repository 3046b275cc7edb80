/* shaderlang_matrix.c - the shader-language translator (shaderlang.c): square matrices.
 *
 * A matrix is a struct of vectors (so declarations, parameters, returns, out arguments and
 * assignments are the structs' code): GLSL's matN (also matNxN) holds its columns, HLSL's
 * floatNxN (and halfNxN) its rows, so that m[i] is what each language says it is (a column, a
 * row). The operations work on the mathematical element A(r, c) whatever the layout: GLSL's
 * `*` of a matrix and a vector or two matrices, HLSL's mul(), transpose(); `+ - / *` between
 * two matrices of HLSL, or a matrix and a number, are component-wise. Constructors take one
 * number (the diagonal), N vectors (GLSL: columns; HLSL: rows) or N*N numbers (GLSL:
 * column-major; HLSL: row-major), as the languages do. */
#define _POSIX_C_SOURCE 200809L
#include "shaderlang.h"
#include "shaderlang_internal.h"

#include <stdio.h>
#include <string.h>

static const struct tok vec_field[4] = { { K_ID, 0, 0, "c0", 2 }, { K_ID, 0, 0, "c1", 2 },
                                         { K_ID, 0, 0, "c2", 2 }, { K_ID, 0, 0, "c3", 2 } };
static const struct tok mat_name[2][3] = { { { K_ID, 0, 0, "mat2", 4 }, { K_ID, 0, 0, "mat3", 4 },
                                             { K_ID, 0, 0, "mat4", 4 } },
                                           { { K_ID, 0, 0, "float2x2", 8 }, { K_ID, 0, 0, "float3x3", 8 },
                                             { K_ID, 0, 0, "float4x4", 8 } } };
/* Constant definitions, filled on first use (the same for every run of the process). */
static struct sdef mat_def[2][3];

/* The definition of an n x n matrix, by rows (HLSL) or by columns (GLSL). */
const struct sdef *sl_matrix_def(int n, int rows)
{
    struct sdef *d = &mat_def[rows][n - 2];
    if (!d->name) {
        d->nfields = n;
        d->is_matrix = rows ? 2 : 1;
        for (int i = 0; i < n; ++i) {
            d->fname[i] = &vec_field[i];
            d->fty[i] = (struct type){ .b = B_FLOAT, .n = n };
        }
        d->name = &mat_name[rows][n - 2];
    }
    return d;
}

int sl_is_matrix(struct type t) { return t.b == B_STRUCT && t.st->is_matrix; }

/* The name of a matrix type: 2..4 and 1 by rows (HLSL), 0 by columns (GLSL); 0 if none. */
int sl_matrix_of_name(const char *w, int *n, int *rows)
{
    static const struct { const char *name; int n, rows; } names[] = {
        { "mat2", 2, 0 }, { "mat3", 3, 0 }, { "mat4", 4, 0 }, { "mat2x2", 2, 0 }, { "mat3x3", 3, 0 },
        { "mat4x4", 4, 0 }, { "float2x2", 2, 1 }, { "float3x3", 3, 1 }, { "float4x4", 4, 1 }, { "half2x2", 2, 1 },
        { "half3x3", 3, 1 }, { "half4x4", 4, 1 }, { "min16float2x2", 2, 1 }, { "min16float3x3", 3, 1 },
        { "min16float4x4", 4, 1 }, { NULL, 0, 0 } };
    for (int i = 0; names[i].name; ++i)
        if (strcmp(w, names[i].name) == 0) {
            *n = names[i].n;
            *rows = names[i].rows;
            return 1;
        }
    return 0;
}

/* A(r, c) of a matrix value. */
static const char *elem(struct val a, int r, int c)
{
    return a.t.st->is_matrix == 2 ? a.f[r].c[c] : a.f[c].c[r];
}

/* An n x n matrix of the layout of `like` from its elements e[r][c]. */
static struct val from_elems(struct sl *S, struct type like, const char *e[4][4])
{
    int n = like.st->nfields;
    struct val r = { .t = like };
    r.f = sl_arena_alloc(S, sizeof *r.f * (size_t)n);
    for (int i = 0; i < n; ++i) {
        r.f[i].t = (struct type){ .b = B_FLOAT, .n = n };
        for (int k = 0; k < n; ++k)
            r.f[i].c[k] = like.st->is_matrix == 2 ? e[i][k] : e[k][i];
    }
    return sl_temp_val(S, r);
}

struct val sl_matrix_transpose(struct sl *S, struct val a, const struct tok *where)
{
    if (!sl_is_matrix(a.t))
        FAIL(S, where, "transpose of a %s (a matrix is expected)", sl_type_name(S, a.t));
    const char *e[4][4];
    int n = a.t.st->nfields;
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
            e[r][c] = elem(a, c, r);
    return from_elems(S, a.t, e);
}

static const char *sum_of_products(struct sl *S, const char **x, const char **y, int n)
{
    const char *s = sl_sfmt(S, "%s * %s", x[0], y[0]);
    for (int k = 1; k < n; ++k)
        s = sl_sfmt(S, "%s + %s * %s", s, x[k], y[k]);
    return sl_temp_real(S, sl_sfmt(S, "(%s)", s));
}

/* The product a b as mathematics has it (HLSL's mul, GLSL's * of a matrix): matrix by vector
 * (a column), vector by matrix (a row), matrix by matrix; numbers scale. */
struct val sl_matrix_mul(struct sl *S, struct val a, struct val b, const struct tok *where)
{
    int am = sl_is_matrix(a.t), bm = sl_is_matrix(b.t);
    if (!am && !bm)
        FAIL(S, where, "mul of a %s and a %s: a matrix is expected", sl_type_name(S, a.t), sl_type_name(S, b.t));
    if ((!am && (a.t.b != B_FLOAT && a.t.b != B_INT)) || (!bm && (b.t.b != B_FLOAT && b.t.b != B_INT)))
        FAIL(S, where, "mul of a %s and a %s", sl_type_name(S, a.t), sl_type_name(S, b.t));
    if (!am && a.t.n == 1)
        return sl_matrix_arith(S, '*', a, b, where);
    if (!bm && b.t.n == 1)
        return sl_matrix_arith(S, '*', a, b, where);
    int n = am ? a.t.st->nfields : b.t.st->nfields;
    if ((am && bm && a.t.st->nfields != b.t.st->nfields) || (!am && a.t.n != n) || (!bm && b.t.n != n))
        FAIL(S, where, "mul of a %s and a %s: the sizes differ", sl_type_name(S, a.t), sl_type_name(S, b.t));
    if (!am)
        a = sl_temp_val(S, sl_to_float(S, a, where));
    if (!bm)
        b = sl_temp_val(S, sl_to_float(S, b, where));
    const char *x[4], *y[4];
    if (am && bm) {
        const char *e[4][4];
        for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c) {
                for (int k = 0; k < n; ++k) {
                    x[k] = elem(a, r, k);
                    y[k] = elem(b, k, c);
                }
                e[r][c] = sum_of_products(S, x, y, n);
            }
        return from_elems(S, a.t, e);
    }
    struct val v = { .t = { .b = B_FLOAT, .n = n } };
    for (int i = 0; i < n; ++i) {
        for (int k = 0; k < n; ++k) {
            x[k] = am ? elem(a, i, k) : a.c[k];
            y[k] = am ? b.c[k] : elem(b, k, i);
        }
        v.c[i] = sum_of_products(S, x, y, n);
    }
    return v;
}

/* a OP b where one is a matrix: GLSL's * of a matrix and a matrix or a vector is the product;
 * otherwise component by component (a number applies to every element). */
struct val sl_matrix_arith(struct sl *S, int op, struct val a, struct val b, const struct tok *where)
{
    int am = sl_is_matrix(a.t), bm = sl_is_matrix(b.t);
    const struct val *m = am ? &a : &b;
    int glsl = m->t.st->is_matrix == 1;
    if (op == '*' && glsl && ((am && bm) || (am && b.t.n > 1) || (bm && a.t.n > 1)))
        return sl_matrix_mul(S, a, b, where);
    if (am && bm && !sl_same_type(a.t, b.t))
        FAIL(S, where, "'%s' of a %s and a %s", sl_op_text(op), sl_type_name(S, a.t), sl_type_name(S, b.t));
    if ((!am && a.t.n > 1) || (!bm && b.t.n > 1))
        FAIL(S, where, "'%s' of a %s and a %s (mul(M, v) multiplies a matrix and a vector)", sl_op_text(op),
             sl_type_name(S, a.t), sl_type_name(S, b.t));
    int n = m->t.st->nfields;
    struct val r = { .t = m->t };
    r.f = sl_arena_alloc(S, sizeof *r.f * (size_t)n);
    if (!am)
        a = sl_temp_val(S, sl_to_float(S, a, where));
    if (!bm)
        b = sl_temp_val(S, sl_to_float(S, b, where));
    for (int i = 0; i < n; ++i)
        r.f[i] = sl_arith(S, op, am ? a.f[i] : a, bm ? b.f[i] : b, where);
    return sl_temp_val(S, r);
}

/* TYPE(...) of a matrix type t from the constructor's values. */
struct val sl_matrix_construct(struct sl *S, struct type t, struct val *parts, int nparts, const struct tok *where)
{
    int n = t.st->nfields;
    const char *e[4][4];
    int by_rows = t.st->is_matrix == 2;
    if (nparts == 1 && sl_is_matrix(parts[0].t)) {
        if (!sl_same_type(parts[0].t, t) && parts[0].t.st->nfields != n)
            FAIL(S, where, "%s of a %s", sl_type_name(S, t), sl_type_name(S, parts[0].t));
        for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c)
                e[r][c] = elem(parts[0], r, c);
        return from_elems(S, t, e);
    }
    if (nparts == 1 && parts[0].t.n == 1 && !sl_is_matrix(parts[0].t)) {
        /* a number: the diagonal */
        const char *d = sl_temp_real(S, sl_to_float(S, parts[0], where).c[0]);
        for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c)
                e[r][c] = r == c ? d : "RSPLAT(0.0)";
        return from_elems(S, t, e);
    }
    /* the components in order: N vectors or N*N numbers, by columns (GLSL) or rows (HLSL) */
    const char *flat[16];
    int k = 0;
    for (int i = 0; i < nparts; ++i) {
        if (sl_is_matrix(parts[i].t) || parts[i].t.b == B_STRUCT)
            FAIL(S, where, "%s(...) of a %s", sl_type_name(S, t), sl_type_name(S, parts[i].t));
        struct val v = sl_to_float(S, parts[i], where);
        for (int j = 0; j < v.t.n; ++j) {
            if (k == 16)
                FAIL(S, where, "%s(...) needs %d components, these give more", sl_type_name(S, t), n * n);
            flat[k++] = v.c[j];
        }
    }
    if (k != n * n)
        FAIL(S, where, "%s(...) needs %d components (or one number, the diagonal), these give %d", sl_type_name(S, t),
             n * n, k);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            if (by_rows)
                e[i][j] = flat[i * n + j];
            else
                e[j][i] = flat[i * n + j];
        }
    return from_elems(S, t, e);
}
