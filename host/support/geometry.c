/* geometry.c - OBJ reader, POV-Ray bicubic_patch reader, Bezier tessellation and smooth
 * normals for the image passes (see geometry.h). */
#include "geometry.h"
#include "errmsg.h"
#include "infile.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

void mesh_free(struct mesh *m)
{
    if (!m)
        return;
    free(m->pos);
    free(m->nrm);
    free(m->tri);
    memset(m, 0, sizeof *m);
}

/* A scene file is text of at most this many bytes (the packaged teapot is 20 KB, the bunny
 * 2.4 MB). */
#define SCENE_FILE_MAX ((size_t)256 << 20)

/* Whole file into a NUL-terminated buffer: a regular file (no FIFO, device or folder:
 * infile.h) of at most SCENE_FILE_MAX bytes, whose first 4096 bytes hold no NUL byte; the size
 * and those bytes are checked before the rest is read, so `--teapot-file /dev/zero` or a large
 * binary file is refused at once. expected: what the file should be, for the binary case.
 * Returns 0, 2 (bad input) or 3 (out of memory, read error). */
static int read_text_file(const char *path, const char *expected, char **text, size_t *len, char *err,
                          size_t errlen)
{
    *text = NULL;
    *len = 0;
    struct stat st;
    char why[256];
    int fd = infile_open(path, 0, &st, why, sizeof why);
    if (fd < 0) {
        set_err(err, errlen, "%s: cannot read: %s", path, why);
        return 2;
    }
    if ((unsigned long long)st.st_size > SCENE_FILE_MAX) {
        set_err(err, errlen, "%s: %lld bytes, larger than a scene file may be (accepted: at most %zu bytes of text)",
                path, (long long)st.st_size, SCENE_FILE_MAX);
        close(fd);
        return 2;
    }
    size_t cap = (size_t)st.st_size, n = 0;
    char *buf = malloc(cap + 1);
    if (!buf) {
        close(fd);
        set_err(err, errlen, "%s: out of memory", path);
        return 3;
    }
    while (n < cap) {
        ssize_t got = read(fd, buf + n, cap - n);
        if (got < 0 && errno == EINTR)
            continue;
        if (got < 0) {
            set_err(err, errlen, "%s: read error: %s", path, strerror(errno));
            free(buf);
            close(fd);
            return 3;
        }
        if (got == 0)
            break;
        n += (size_t)got;
        if (n >= 4096 || n == cap) {
            size_t head = n < 4096 ? n : 4096;
            const char *nul = memchr(buf, '\0', head);
            if (nul) {
                long at = 1;
                for (const char *q = buf; q < nul; ++q)
                    at += *q == '\n';
                set_err(err, errlen, "%s:%ld: %s; found binary data", path, at, expected);
                free(buf);
                close(fd);
                return 2;
            }
        }
    }
    close(fd);
    buf[n] = '\0';
    *text = buf;
    *len = n;
    return 0;
}

/* ---------------------------------------------------------------- growable arrays */

/* A growable array of n elements (cap allocated); the element type is the caller's. */
struct grow {
    void *v;
    size_t n, cap;
};

/* Appends the three elements at xyz (each of size elem) to a, growing it to twice its
 * capacity (3 x 1024 at first) when full; -1 when out of memory (a stays as it was). */
static int vec_push3(struct grow *a, size_t elem, const void *xyz)
{
    if (a->n + 3 > a->cap) {
        size_t nc = a->cap ? 2 * a->cap : 3 * 1024;
        void *nv = realloc(a->v, nc * elem);
        if (!nv)
            return -1;
        a->v = nv;
        a->cap = nc;
    }
    memcpy((char *)a->v + a->n * elem, xyz, 3 * elem);
    a->n += 3;
    return 0;
}

/* ---------------------------------------------------------------- OBJ */

/* Next whitespace-separated token of a line; NULL at the end. */
static char *next_token(char **cursor)
{
    char *s = *cursor;
    while (*s == ' ' || *s == '\t' || *s == '\r')
        s++;
    if (*s == '\0') {
        *cursor = s;
        return NULL;
    }
    char *start = s;
    while (*s && *s != ' ' && *s != '\t' && *s != '\r')
        s++;
    if (*s)
        *s++ = '\0';
    *cursor = s;
    return start;
}

static int parse_finite(const char *tok, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(tok, &end);
    if (end == tok || *end != '\0' || errno == ERANGE || !isfinite(v))
        return -1;
    *out = v;
    return 0;
}

/* One index of a face corner: 1-based, or negative counting back from the last element
 * defined so far (OBJ's relative form). Returns the 0-based index or -1. */
static long resolve_index(const char *s, size_t len, size_t defined)
{
    if (len == 0 || len > 20)
        return -1;
    char buf[24];
    memcpy(buf, s, len);
    buf[len] = '\0';
    char *end;
    errno = 0;
    long v = strtol(buf, &end, 10);
    if (end == buf || *end != '\0' || errno == ERANGE || v == 0)
        return -1;
    if (v > 0)
        return (size_t)v <= defined ? v - 1 : -1;
    if ((size_t)(-v) > defined)
        return -1;
    return (long)defined + v;
}

/* An OBJ file being read: its vertices and triangles so far, how many vt and vn it has
 * defined, the line being read and where a message goes. */
struct obj_state {
    struct grow pos;   /* float x, y, z per vertex */
    struct grow tri;   /* uint32_t corners per triangle */
    size_t ntex, nnrm;
    long line_no;
    const char *name;
    char *err;
    size_t errlen;
};

/* Until a statement of the format is seen, a line that is not one means the file is
 * something else (a binary mesh, a PLY): say which format is expected. */
static const char *const obj_expected =
    "not a Wavefront OBJ file (expected text lines of v, vt, vn and f statements)";

/* Refuses a file with control bytes other than whitespace (2, with the line of the first). */
static int obj_binary_check(const char *text, size_t len, const char *name, char *err, size_t errlen)
{
    for (size_t k = 0; k < len; ++k) {
        unsigned char ch = (unsigned char)text[k];
        if (ch == 0 || (ch < 0x20 && ch != '\t' && ch != '\n' && ch != '\r' && ch != '\v' && ch != '\f') || ch == 0x7f) {
            long at = 1;
            for (size_t j = 0; j < k; ++j)
                at += text[j] == '\n';
            set_err(err, errlen, "%s:%ld: %s; found binary data", name, at, obj_expected);
            return 2;
        }
    }
    return 0;
}

/* A v, vn or vt statement (kw) with its numbers after cur: a vertex is kept, the others
 * counted. Returns 0, 2 (malformed) or 3 (out of memory). */
static int obj_vertex(struct obj_state *S, const char *kw, char *cur)
{
    const char *name = S->name;
    long line_no = S->line_no;
    int want_min = kw[1] == 't' ? 1 : 3;
    double val[3] = {0, 0, 0};
    int count = 0;
    char *tok;
    while ((tok = next_token(&cur)) != NULL) {
        double x;
        if (parse_finite(tok, &x) != 0) {
            set_err(S->err, S->errlen, "%s:%ld: '%s' statement: '%s' is not a finite number",
                    name, line_no, kw, tok);
            return 2;
        }
        if (count < 3)
            val[count] = x;
        count++;
    }
    /* v may carry w or an RGB colour after x y z; vt has 1 to 3 numbers */
    int want_max = kw[1] == '\0' ? 7 : 3;
    if (count < want_min || count > want_max) {
        set_err(S->err, S->errlen, "%s:%ld: '%s' needs %d to %d numbers, found %d", name,
                line_no, kw, want_min, want_max, count);
        return 2;
    }
    if (kw[1] == '\0') {
        if (S->pos.n / 3 >= UINT32_MAX) {
            set_err(S->err, S->errlen, "%s:%ld: too many vertices", name, line_no);
            return 2;
        }
        const float xyz[3] = { (float)val[0], (float)val[1], (float)val[2] };
        if (vec_push3(&S->pos, sizeof xyz[0], xyz) != 0) {
            set_err(S->err, S->errlen, "%s: out of memory", name);
            return 3;
        }
    } else if (kw[1] == 'n') {
        S->nnrm++;
    } else {
        S->ntex++;
    }
    return 0;
}

/* One face corner (v, v/vt, v/vt/vn or v//vn): its 0-based vertex in *vi; 2 when malformed
 * or out of range. */
static int obj_corner(struct obj_state *S, const char *tok, size_t nv, long *vi)
{
    const char *s1 = strchr(tok, '/');
    size_t vlen = s1 ? (size_t)(s1 - tok) : strlen(tok);
    *vi = resolve_index(tok, vlen, nv);
    if (*vi < 0) {
        set_err(S->err, S->errlen,
                "%s:%ld: face corner '%s': vertex index must be a non-zero integer "
                "referring to one of the %zu vertices defined so far",
                S->name, S->line_no, tok, nv);
        return 2;
    }
    if (s1) {
        const char *s2 = strchr(s1 + 1, '/');
        size_t tlen = s2 ? (size_t)(s2 - s1 - 1) : strlen(s1 + 1);
        int bad = 0;
        if (tlen > 0 && resolve_index(s1 + 1, tlen, S->ntex) < 0)
            bad = 1;
        if (!s2 && tlen == 0)
            bad = 1; /* "v/" */
        if (s2) {
            size_t nlen = strlen(s2 + 1);
            if (strchr(s2 + 1, '/') || resolve_index(s2 + 1, nlen, S->nnrm) < 0)
                bad = 1;
        }
        if (bad) {
            set_err(S->err, S->errlen,
                    "%s:%ld: face corner '%s': malformed or out-of-range texture/"
                    "normal index (%zu vt and %zu vn defined so far)",
                    S->name, S->line_no, tok, S->ntex, S->nnrm);
            return 2;
        }
    }
    return 0;
}

/* An f statement with its corners after cur, kept as a fan of triangles. Returns 0, 2
 * (malformed) or 3 (out of memory). */
static int obj_face(struct obj_state *S, char *cur)
{
    /* Face corners of one polygon; polygons larger than this are unusual enough to refuse. */
    enum { MAX_CORNERS = 256 };
    uint32_t corner[MAX_CORNERS];
    size_t nv = S->pos.n / 3;
    int ncorner = 0;
    char *tok;
    while ((tok = next_token(&cur)) != NULL) {
        if (ncorner == MAX_CORNERS) {
            set_err(S->err, S->errlen, "%s:%ld: face has more than %d corners", S->name,
                    S->line_no, MAX_CORNERS);
            return 2;
        }
        long vi;
        if (obj_corner(S, tok, nv, &vi) != 0)
            return 2;
        corner[ncorner++] = (uint32_t)vi;
    }
    if (ncorner < 3) {
        set_err(S->err, S->errlen, "%s:%ld: face needs at least 3 corners, found %d", S->name,
                S->line_no, ncorner);
        return 2;
    }
    for (int k = 1; k + 1 < ncorner; k++) {
        const uint32_t abc[3] = { corner[0], corner[k], corner[k + 1] };
        if (vec_push3(&S->tri, sizeof abc[0], abc) != 0) {
            set_err(S->err, S->errlen, "%s: out of memory", S->name);
            return 3;
        }
    }
    return 0;
}

int obj_parse(const char *text, size_t len, const char *name, struct mesh *out, char *err,
              size_t errlen)
{
    memset(out, 0, sizeof *out);
    char *copy = malloc(len + 1);
    if (!copy) {
        set_err(err, errlen, "%s: out of memory", name);
        return 3;
    }
    memcpy(copy, text, len);
    copy[len] = '\0';

    struct obj_state S = { .name = name, .err = err, .errlen = errlen };
    int rc = 0;
    int seen_obj = 0;
    if (obj_binary_check(text, len, name, err, errlen) != 0) {
        free(copy);
        return 2;
    }

    char *line = copy;
    while (line && rc == 0) {
        char *nl = memchr(line, '\n', (size_t)(copy + len - line));
        if (nl)
            *nl = '\0';
        else if (*line == '\0')
            break; /* nothing after the last newline */
        S.line_no++;
        char *hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        if (strchr(line, '\\')) {
            if (!seen_obj)
                set_err(err, errlen, "%s:%ld: %s", name, S.line_no, obj_expected);
            else
                set_err(err, errlen, "%s:%ld: line continuation '\\' is not supported", name,
                        S.line_no);
            rc = 2;
            break;
        }
        char *cur = line;
        char *kw = next_token(&cur);
        if (!kw) {
            /* blank or comment line */
        } else if (strcmp(kw, "v") == 0 || strcmp(kw, "vn") == 0 || strcmp(kw, "vt") == 0) {
            seen_obj = 1;
            rc = obj_vertex(&S, kw, cur);
        } else if (strcmp(kw, "f") == 0) {
            seen_obj = 1;
            rc = obj_face(&S, cur);
        } else if (strcmp(kw, "o") == 0 || strcmp(kw, "g") == 0 || strcmp(kw, "s") == 0 ||
                   strcmp(kw, "usemtl") == 0 || strcmp(kw, "mtllib") == 0 ||
                   strcmp(kw, "l") == 0 || strcmp(kw, "p") == 0 || strcmp(kw, "vp") == 0) {
            /* grouping, materials, points and lines: nothing to render from them */
            seen_obj = 1;
        } else if (!seen_obj) {
            set_err(err, errlen, "%s:%ld: %s; found '%.40s'", name, S.line_no, obj_expected, kw);
            rc = 2;
        } else {
            set_err(err, errlen, "%s:%ld: unknown or unsupported statement '%s'", name, S.line_no,
                    kw);
            rc = 2;
        }
        line = nl ? nl + 1 : NULL;
    }
    free(copy);
    if (rc == 0 && S.tri.n == 0) {
        set_err(err, errlen, "%s:%ld: no faces ('f' statements) in the file", name, S.line_no);
        rc = 2;
    }
    if (rc != 0) {
        free(S.pos.v);
        free(S.tri.v);
        return rc;
    }
    out->nverts = S.pos.n / 3;
    out->ntris = S.tri.n / 3;
    out->pos = S.pos.v;
    out->tri = S.tri.v;
    out->nrm = calloc(out->nverts * 3, sizeof(float));
    if (!out->nrm) {
        mesh_free(out);
        set_err(err, errlen, "%s: out of memory", name);
        return 3;
    }
    return 0;
}

int obj_read(const char *path, struct mesh *out, char *err, size_t errlen)
{
    char *text;
    size_t len;
    memset(out, 0, sizeof *out);
    int rc = read_text_file(path, "not a Wavefront OBJ file (expected text lines of v, vt, vn and f statements)",
                            &text, &len, err, errlen);
    if (rc)
        return rc;
    rc = obj_parse(text, len, path, out, err, errlen);
    free(text);
    return rc;
}

/* ---------------------------------------------------------------- normals */

double vec3_normalize(double *a)
{
    double l = sqrt(vec3_dot(a, a));
    if (l > 0)
        for (int c = 0; c < 3; c++)
            a[c] /= l;
    return l;
}

static double len3(const double *a)
{
    return sqrt(vec3_dot(a, a));
}

int mesh_smooth_normals(struct mesh *m, char *err, size_t errlen)
{
    double *acc = calloc(m->nverts * 3, sizeof *acc);
    if (!acc) {
        set_err(err, errlen, "smooth normals: out of memory");
        return 3;
    }
    for (size_t t = 0; t < m->ntris; t++) {
        const uint32_t *ix = m->tri + 3 * t;
        double p[3][3];
        for (int k = 0; k < 3; k++)
            for (int c = 0; c < 3; c++)
                p[k][c] = m->pos[3 * (size_t)ix[k] + c];
        double e1[3], e2[3], fn[3];
        vec3_sub(p[1], p[0], e1);
        vec3_sub(p[2], p[0], e2);
        vec3_cross(e1, e2, fn);
        double fl = len3(fn);
        if (!(fl > 0))
            continue; /* degenerate: no direction to contribute */
        for (int c = 0; c < 3; c++)
            fn[c] /= fl;
        for (int k = 0; k < 3; k++) {
            double a[3], b[3], ab[3];
            vec3_sub(p[(k + 1) % 3], p[k], a);
            vec3_sub(p[(k + 2) % 3], p[k], b);
            vec3_cross(a, b, ab);
            /* atan2 keeps the corner angle accurate near 0 and pi, unlike acos(dot) */
            double angle = atan2(len3(ab), vec3_dot(a, b));
            for (int c = 0; c < 3; c++)
                acc[3 * (size_t)ix[k] + c] += angle * fn[c];
        }
    }
    for (size_t v = 0; v < m->nverts; v++) {
        double *a = acc + 3 * v;
        double l = len3(a);
        if (l > 0) {
            for (int c = 0; c < 3; c++)
                m->nrm[3 * v + c] = (float)(a[c] / l);
        } else {
            m->nrm[3 * v + 0] = 0.0f;
            m->nrm[3 * v + 1] = 0.0f;
            m->nrm[3 * v + 2] = 1.0f;
        }
    }
    free(acc);
    return 0;
}

void mesh_bounds(const struct mesh *m, double lo[3], double hi[3])
{
    for (int c = 0; c < 3; c++) {
        lo[c] = m->nverts ? INFINITY : 0.0;
        hi[c] = m->nverts ? -INFINITY : 0.0;
    }
    for (size_t v = 0; v < m->nverts; v++)
        for (int c = 0; c < 3; c++) {
            double x = m->pos[3 * v + c];
            if (x < lo[c])
                lo[c] = x;
            if (x > hi[c])
                hi[c] = x;
        }
}

/* ---------------------------------------------------------------- POV-Ray patches */

enum tok_kind { TOK_END, TOK_IDENT, TOK_NUMBER, TOK_PUNCT };

struct lexer {
    const char *s, *end;
    const char *name;
    long line;
    /* current token */
    enum tok_kind kind;
    char text[64];
    double number;
    long tok_line;
};

/* The token from start to the lexer's position as its text (cut to the room there is). */
static void lex_keep_text(struct lexer *lx, const char *start)
{
    size_t n = (size_t)(lx->s - start);
    if (n >= sizeof lx->text)
        n = sizeof lx->text - 1;
    memcpy(lx->text, start, n);
    lx->text[n] = '\0';
}

/* Advances to the next token; returns -1 with a message on an unterminated comment or a
 * number that does not parse. */
static int lex_next(struct lexer *lx, char *err, size_t errlen)
{
    for (;;) {
        while (lx->s < lx->end && isspace((unsigned char)*lx->s)) {
            if (*lx->s == '\n')
                lx->line++;
            lx->s++;
        }
        if (lx->s + 1 < lx->end && lx->s[0] == '/' && lx->s[1] == '/') {
            while (lx->s < lx->end && *lx->s != '\n')
                lx->s++;
            continue;
        }
        if (lx->s + 1 < lx->end && lx->s[0] == '/' && lx->s[1] == '*') {
            long start = lx->line;
            lx->s += 2;
            while (lx->s + 1 < lx->end && !(lx->s[0] == '*' && lx->s[1] == '/')) {
                if (*lx->s == '\n')
                    lx->line++;
                lx->s++;
            }
            if (lx->s + 1 >= lx->end) {
                set_err(err, errlen, "%s:%ld: unterminated /* comment", lx->name, start);
                return -1;
            }
            lx->s += 2;
            continue;
        }
        break;
    }
    lx->tok_line = lx->line;
    lx->text[0] = '\0';
    if (lx->s >= lx->end) {
        lx->kind = TOK_END;
        return 0;
    }
    char c = *lx->s;
    int signed_number = (c == '-' || c == '+') && lx->s + 1 < lx->end &&
                        (isdigit((unsigned char)lx->s[1]) || lx->s[1] == '.');
    if (isdigit((unsigned char)c) || c == '.' || signed_number) {
        const char *start = lx->s;
        lx->s++;
        while (lx->s < lx->end &&
               (isalnum((unsigned char)*lx->s) || *lx->s == '.' ||
                ((*lx->s == '-' || *lx->s == '+') && (lx->s[-1] == 'e' || lx->s[-1] == 'E'))))
            lx->s++;
        lex_keep_text(lx, start);
        if (parse_finite(lx->text, &lx->number) != 0) {
            set_err(err, errlen, "%s:%ld: '%s' is not a finite number", lx->name, lx->tok_line,
                    lx->text);
            return -1;
        }
        lx->kind = TOK_NUMBER;
        return 0;
    }
    if (isalpha((unsigned char)c) || c == '_') {
        const char *start = lx->s;
        while (lx->s < lx->end && (isalnum((unsigned char)*lx->s) || *lx->s == '_'))
            lx->s++;
        lex_keep_text(lx, start);
        lx->kind = TOK_IDENT;
        return 0;
    }
    if (c == '"') { /* a string literal: skipped whole, it may hold any character */
        lx->s++;
        while (lx->s < lx->end && *lx->s != '"' && *lx->s != '\n')
            lx->s++;
        if (lx->s >= lx->end || *lx->s != '"') {
            set_err(err, errlen, "%s:%ld: unterminated string", lx->name, lx->tok_line);
            return -1;
        }
        lx->s++;
        lx->kind = TOK_IDENT;
        strcpy(lx->text, "\"\"");
        return 0;
    }
    lx->text[0] = c;
    lx->text[1] = '\0';
    lx->s++;
    lx->kind = TOK_PUNCT;
    return 0;
}

static const char *tok_describe(const struct lexer *lx)
{
    return lx->kind == TOK_END ? "end of file" : lx->text;
}

static int lex_expect_punct(struct lexer *lx, char want, const char *what, char *err,
                            size_t errlen)
{
    if (lex_next(lx, err, errlen) != 0)
        return -1;
    if (lx->kind != TOK_PUNCT || lx->text[0] != want) {
        set_err(err, errlen, "%s:%ld: expected '%c' %s, found '%s'", lx->name, lx->tok_line,
                want, what, tok_describe(lx));
        return -1;
    }
    return 0;
}

/* Reads "x , y , z >" after a '<'. */
static int lex_vector_rest(struct lexer *lx, double v[3], char *err, size_t errlen)
{
    for (int k = 0; k < 3; k++) {
        if (lex_next(lx, err, errlen) != 0)
            return -1;
        if (lx->kind != TOK_NUMBER) {
            set_err(err, errlen, "%s:%ld: control point: expected a number, found '%s'",
                    lx->name, lx->tok_line, tok_describe(lx));
            return -1;
        }
        v[k] = lx->number;
        if (lex_expect_punct(lx, k < 2 ? ',' : '>',
                             k < 2 ? "between control point coordinates"
                                   : "closing a control point (3 coordinates)",
                             err, errlen) != 0)
            return -1;
    }
    return 0;
}

int patches_parse(const char *text, size_t len, const char *name, struct bezier_patch **out,
                  size_t *count, char *err, size_t errlen)
{
    *out = NULL;
    *count = 0;
    struct lexer lx = {.s = text, .end = text + len, .name = name, .line = 1};
    struct bezier_patch *arr = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (lex_next(&lx, err, errlen) != 0)
            goto fail;
        if (lx.kind == TOK_END)
            break;
        if (lx.kind != TOK_IDENT || strcmp(lx.text, "bicubic_patch") != 0)
            continue;
        long patch_line = lx.tok_line;
        if (lex_expect_punct(&lx, '{', "after bicubic_patch", err, errlen) != 0)
            goto fail;
        if (n == cap) {
            size_t nc = cap ? 2 * cap : 32;
            struct bezier_patch *na = realloc(arr, nc * sizeof *na);
            if (!na) {
                set_err(err, errlen, "%s: out of memory", name);
                free(arr);
                return 3;
            }
            arr = na;
            cap = nc;
        }
        struct bezier_patch *p = &arr[n];
        int points = 0, depth = 1;
        while (depth > 0) {
            if (lex_next(&lx, err, errlen) != 0)
                goto fail;
            if (lx.kind == TOK_END) {
                set_err(err, errlen,
                        "%s:%ld: bicubic_patch starting here is not closed (end of file after "
                        "%d of its 16 control points)",
                        name, patch_line, points);
                goto fail;
            }
            if (lx.kind == TOK_PUNCT && lx.text[0] == '{') {
                depth++;
            } else if (lx.kind == TOK_PUNCT && lx.text[0] == '}') {
                depth--;
                if (depth == 0 && points < 16) {
                    set_err(err, errlen,
                            "%s:%ld: bicubic_patch starting at line %ld has %d control points, "
                            "16 needed",
                            name, lx.tok_line, patch_line, points);
                    goto fail;
                }
            } else if (depth == 1 && lx.kind == TOK_PUNCT && lx.text[0] == '<') {
                if (points == 16) {
                    set_err(err, errlen,
                            "%s:%ld: bicubic_patch starting at line %ld: a 17th vector; only "
                            "16 control points are allowed and patch transforms are not "
                            "supported",
                            name, lx.tok_line, patch_line);
                    goto fail;
                }
                if (lex_vector_rest(&lx, p->cp[points], err, errlen) != 0)
                    goto fail;
                points++;
            } else if (depth == 1 && lx.kind == TOK_IDENT &&
                       (strcmp(lx.text, "translate") == 0 || strcmp(lx.text, "rotate") == 0 ||
                        strcmp(lx.text, "scale") == 0 || strcmp(lx.text, "matrix") == 0 ||
                        strcmp(lx.text, "transform") == 0)) {
                set_err(err, errlen,
                        "%s:%ld: '%s' inside a bicubic_patch is not supported (control points "
                        "are taken as written)",
                        name, lx.tok_line, lx.text);
                goto fail;
            }
            /* keywords and values before the points (type, flatness, u_steps, v_steps) and
               modifiers after them (texture { ... }) do not change the surface */
        }
        n++;
    }
    if (n == 0) {
        set_err(err, errlen, "%s:%ld: no bicubic_patch found (expected a POV-Ray file with bicubic_patch blocks, "
                "as the teapot of povray-examples)", name, lx.line);
        goto fail;
    }
    *out = arr;
    *count = n;
    return 0;
fail:
    free(arr);
    return 2;
}

int patches_read(const char *path, struct bezier_patch **out, size_t *count, char *err,
                 size_t errlen)
{
    char *text;
    size_t len;
    *out = NULL;
    *count = 0;
    int rc = read_text_file(path, "not a POV-Ray file (expected a text file with bicubic_patch blocks)", &text,
                            &len, err, errlen);
    if (rc)
        return rc;
    rc = patches_parse(text, len, path, out, count, err, errlen);
    free(text);
    return rc;
}

static void bernstein(double t, double b[4], double db[4])
{
    double s = 1.0 - t;
    b[0] = s * s * s;
    b[1] = 3.0 * t * s * s;
    b[2] = 3.0 * t * t * s;
    b[3] = t * t * t;
    db[0] = -3.0 * s * s;
    db[1] = 3.0 * s * s - 6.0 * t * s;
    db[2] = 6.0 * t * s - 3.0 * t * t;
    db[3] = 3.0 * t * t;
}

/* Position and the unnormalised normal dP/du x dP/dv. */
static void patch_eval_raw(const struct bezier_patch *p, double u, double v, double pos[3],
                           double n[3])
{
    double bu[4], dbu[4], bv[4], dbv[4];
    bernstein(u, bu, dbu);
    bernstein(v, bv, dbv);
    double du[3] = {0, 0, 0}, dv[3] = {0, 0, 0};
    for (int c = 0; c < 3; c++)
        pos[c] = 0.0;
    for (int i = 0; i < 4; i++)     /* row: v */
        for (int j = 0; j < 4; j++) { /* column: u */
            const double *q = p->cp[4 * i + j];
            for (int c = 0; c < 3; c++) {
                pos[c] += bu[j] * bv[i] * q[c];
                du[c] += dbu[j] * bv[i] * q[c];
                dv[c] += bu[j] * dbv[i] * q[c];
            }
        }
    vec3_cross(du, dv, n);
}

void patch_eval(const struct bezier_patch *p, double u, double v, double pos[3], double nrm[3])
{
    double n[3], scale = 0.0;
    for (int k = 1; k < 16; k++) {
        double d[3];
        vec3_sub(p->cp[k], p->cp[0], d);
        double l = len3(d);
        if (l > scale)
            scale = l;
    }
    patch_eval_raw(p, u, v, pos, n);
    double l = len3(n);
    /* A collapsed side has dP/dv (or dP/du) = 0 there: the normal's limit is approached by
       stepping inside; the steps grow until the cross product is clearly non-zero. */
    double tiny = 1e-10 * scale * scale;
    for (double step = 1e-5; !(l > tiny) && step < 0.2; step *= 4.0) {
        double uu = u < 0.5 ? u + step : u - step;
        double vv = v < 0.5 ? v + step : v - step;
        double dummy[3];
        patch_eval_raw(p, uu, vv, dummy, n);
        l = len3(n);
    }
    if (l > tiny) {
        for (int c = 0; c < 3; c++)
            nrm[c] = n[c] / l;
    } else {
        nrm[0] = 0.0;
        nrm[1] = 0.0;
        nrm[2] = 1.0;
    }
}

int patches_tessellate(const struct bezier_patch *patches, size_t count, int density,
                       struct mesh *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (density < 1 || density > 512) {
        set_err(err, errlen, "tessellation density %d outside [1, 512]", density);
        return 2;
    }
    size_t side = (size_t)density + 1;
    size_t per_patch_v = side * side;
    size_t per_patch_t = 2 * (size_t)density * (size_t)density;
    if (count == 0 || count > UINT32_MAX / per_patch_t || count > UINT32_MAX / per_patch_v) {
        set_err(err, errlen, "tessellation of %zu patches at density %d: too many triangles",
                count, density);
        return 3;
    }
    out->nverts = count * per_patch_v;
    out->ntris = count * per_patch_t;
    out->pos = malloc(out->nverts * 3 * sizeof(float));
    out->nrm = malloc(out->nverts * 3 * sizeof(float));
    out->tri = malloc(out->ntris * 3 * sizeof(uint32_t));
    if (!out->pos || !out->nrm || !out->tri) {
        mesh_free(out);
        set_err(err, errlen, "tessellation: out of memory");
        return 3;
    }
    size_t vbase = 0, t = 0;
    for (size_t pi = 0; pi < count; pi++) {
        for (size_t a = 0; a < side; a++)
            for (size_t b = 0; b < side; b++) {
                double pos[3], nrm[3];
                patch_eval(&patches[pi], (double)a / density, (double)b / density, pos, nrm);
                size_t vi = vbase + a * side + b;
                for (int c = 0; c < 3; c++) {
                    out->pos[3 * vi + c] = (float)pos[c];
                    out->nrm[3 * vi + c] = (float)nrm[c];
                }
            }
        for (size_t a = 0; a < (size_t)density; a++)
            for (size_t b = 0; b < (size_t)density; b++) {
                uint32_t v00 = (uint32_t)(vbase + a * side + b);
                uint32_t v10 = (uint32_t)(vbase + (a + 1) * side + b);
                uint32_t v01 = v00 + 1, v11 = v10 + 1;
                /* (u, then u+v) and (u+v, then v): cross products along +du x dv */
                uint32_t *o = out->tri + 3 * t;
                o[0] = v00;
                o[1] = v10;
                o[2] = v11;
                o[3] = v00;
                o[4] = v11;
                o[5] = v01;
                t += 2;
            }
        vbase += per_patch_v;
    }
    return 0;
}
