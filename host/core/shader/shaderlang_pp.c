/* shaderlang_pp.c - the shader-language translator's preprocessor (shaderlang.c): glslang's.
 *
 * A GLSL/HLSL text with a preprocessor directive (#if, #ifdef, function-like macros, #undef,
 * #line, ...), a __LINE__, or defines (-D NAME=VALUE, the header's "define:" key) goes through
 * the preprocessor of glslang, the Khronos reference front end (Debian's glslang-dev, linked as
 * a library through its C interface): what it keeps is then lexed as the user's text. Its output
 * keeps the lines of the input (a removed line stays as an empty one, #line is passed through),
 * so a token's line is the user's; its column is found again by looking for the token's text in
 * the user's line (sl_pp_column), and a token a macro brought gets the column of the macro's
 * name. docs/user-models.md, "Preprocessor", compares glslang with mcpp and cpp and says why
 * glslang. Without glslang at build time (BRDF_HAVE_GLSLANG unset) the lexer's own object-like
 * #define is all there is, and other directives are refused with that reason. */
#define _POSIX_C_SOURCE 200809L
#include "shaderlang.h"
#include "shaderlang_internal.h"
#include "exitcodes.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef BRDF_HAVE_GLSLANG
#include <glslang/Include/glslang_c_interface.h>
#include <glslang/Public/resource_limits_c.h>
#endif

/* The defines of the command line (-D), for every shader-language file read after them: settings
   of the process's flags, read with the model registry's files (models.c), before any run opens. */
static char cli_defines[SL_MAX_DEFINES][SL_DEFINE_MAX + 1];
static int cli_ndefines;

/* NAME, NAME=VALUE: checks it and writes "NAME VALUE" (VALUE 1 when absent) into out. */
int sl_define_text(const char *arg, char *out, size_t outlen, char *err, size_t errlen, const char *what)
{
    const char *eq = strchr(arg, '=');
    size_t nl = eq ? (size_t)(eq - arg) : strlen(arg);
    int ok = nl > 0 && nl <= SL_NAME_MAX && (isalpha((unsigned char)arg[0]) || arg[0] == '_');
    for (size_t i = 0; ok && i < nl; ++i)
        if (!isalnum((unsigned char)arg[i]) && arg[i] != '_')
            ok = 0;
    if (!ok) {
        snprintf(err, errlen, "%s '%.60s': expected NAME or NAME=VALUE with NAME an identifier of 1 to %d "
                 "characters (letters, digits, _)", what, arg, SL_NAME_MAX);
        return EXIT_USAGE;
    }
    const char *v = eq ? eq + 1 : "1";
    for (const char *p = v; *p; ++p)
        if ((unsigned char)*p < 0x20 || (unsigned char)*p > 0x7e) {
            snprintf(err, errlen, "%s '%.60s': the value has a control character (one line of printable "
                     "characters is accepted)", what, arg);
            return EXIT_USAGE;
        }
    if (nl + 1 + strlen(v) > SL_DEFINE_MAX || !*v) {
        snprintf(err, errlen, "%s '%.60s': the value must have 1 to %d characters", what, arg,
                 SL_DEFINE_MAX - (int)nl - 1);
        return EXIT_USAGE;
    }
    snprintf(out, outlen, "%.*s %s", (int)nl, arg, v);
    return 0;
}

int shaderlang_define(const char *arg, char *err, size_t errlen)
{
    if (cli_ndefines == SL_MAX_DEFINES) {
        snprintf(err, errlen, "-D %.60s: more than %d defines", arg, SL_MAX_DEFINES);
        return EXIT_USAGE;
    }
    if (sl_define_text(arg, cli_defines[cli_ndefines], sizeof cli_defines[0], err, errlen, "-D"))
        return EXIT_USAGE;
    cli_ndefines++;
    return 0;
}

void shaderlang_clear_defines(void) { cli_ndefines = 0; }

int shaderlang_has_preprocessor(void)
{
#ifdef BRDF_HAVE_GLSLANG
    return 1;
#else
    return 0;
#endif
}

/* The first directive of the text other than those the lexer reads itself (#version,
 * #extension, #pragma, object-like #define): its line (1-based within the text), or 0. A
 * #include is refused here: a model reads no file but its own. */
static int needs_preprocessor(struct sl *S, const char *text, size_t len, int first_line)
{
    int line = 1, found = 0;
    for (size_t i = 0; i < len;) {
        size_t j = i;
        while (j < len && (text[j] == ' ' || text[j] == '\t'))
            ++j;
        if (j < len && text[j] == '#') {
            size_t k = j + 1;
            while (k < len && (text[k] == ' ' || text[k] == '\t'))
                ++k;
            size_t w = k;
            while (k < len && isalpha((unsigned char)text[k]))
                ++k;
            int wl = (int)(k - w);
            if (wl == 7 && strncmp(text + w, "include", 7) == 0)
                sl_fail_at(S, line + first_line - 1, (int)(j - i) + 1,
                           "#include is not accepted: a model file reads no other file");
            int own = (wl == 7 && strncmp(text + w, "version", 7) == 0) ||
                      (wl == 9 && strncmp(text + w, "extension", 9) == 0) ||
                      (wl == 6 && strncmp(text + w, "pragma", 6) == 0);
            if (wl == 6 && strncmp(text + w, "define", 6) == 0) {
                /* object-like unless '(' follows the name at once */
                while (k < len && (text[k] == ' ' || text[k] == '\t'))
                    ++k;
                while (k < len && (isalnum((unsigned char)text[k]) || text[k] == '_'))
                    ++k;
                own = !(k < len && text[k] == '(');
            }
            if (!own && !found)
                found = line;
        }
        const char *eol = memchr(text + i, '\n', len - i);
        i = eol ? (size_t)(eol - text) + 1 : len;
        ++line;
    }
    if (!found && sl_uses_word(text, len, "__LINE__"))
        found = 1;
    return found;
}

/* The column, in the user's line, of a token the preprocessor wrote: its text looked for from
 * where the previous token of the line was found; not found (a macro's replacement), the column
 * where the previous search stopped, after blanks: the macro's name there. */
int sl_pp_column(struct sl *S, const struct tok *t, int out_line)
{
    struct sl_pp *pp = &S->pp;
    int src_line = out_line - pp->first_line; /* 0-based line of the user's text */
    if (src_line < 0 || src_line >= pp->nlines)
        return 1;
    const char *ls = pp->src + pp->line_start[src_line];
    const char *le = src_line + 1 < pp->nlines ? pp->src + pp->line_start[src_line + 1] : pp->src + pp->src_len;
    if (src_line != pp->cur_line) {
        pp->cur_line = src_line;
        pp->cursor = 0;
    }
    const char *from = ls + pp->cursor;
    for (const char *p = from; p + t->len <= le; ++p)
        if (memcmp(p, t->p, (size_t)t->len) == 0 &&
            !(t->k == K_ID && ((p > ls && (isalnum((unsigned char)p[-1]) || p[-1] == '_')) ||
                               (p + t->len < le && (isalnum((unsigned char)p[t->len]) || p[t->len] == '_'))))) {
            pp->cursor = (int)(p - ls) + t->len;
            return (int)(p - ls) + 1;
        }
    while (from < le && (*from == ' ' || *from == '\t'))
        ++from;
    return (int)(from - ls) + 1;
}

#ifdef BRDF_HAVE_GLSLANG
/* glslang's first error ("ERROR: 0:12: '#if' : unexpected tokens following directive") as the
 * user's line and message. */
static void __attribute__((noreturn)) fail_from_log(struct sl *S, const char *log, int first_line)
{
    const char *e = strstr(log, "ERROR: ");
    if (!e)
        sl_fail_at(S, 0, 0, "glslang's preprocessor failed without a message");
    e += 7;
    const char *eol = strchr(e, '\n');
    int len = eol ? (int)(eol - e) : (int)strlen(e);
    int string_no = 0, line = 0, used = 0;
    if (sscanf(e, "%d:%d: %n", &string_no, &line, &used) >= 2 && used > 0) {
        e += used;
        len -= used;
    } else {
        line = 0;
    }
    while (len > 0 && isspace((unsigned char)e[len - 1]))
        --len;
    /* "'#if' : message" reads "#if: message" */
    char msg[300];
    const char *sep = len > 2 && e[0] == '\'' ? strstr(e, "' : ") : NULL;
    if (sep && sep - e < len && sep == e + 1)
        snprintf(msg, sizeof msg, "%.*s", len - (int)(sep + 4 - e), sep + 4);
    else if (sep && sep - e < len)
        snprintf(msg, sizeof msg, "%.*s: %.*s", (int)(sep - e - 1), e + 1, len - (int)(sep + 4 - e),
                 sep + 4);
    else
        snprintf(msg, sizeof msg, "%.*s", len, e);
    sl_fail_at(S, line > 0 ? line + first_line - 1 : 0, -1, "%s (glslang's preprocessor)", msg);
}
#endif

/* 1 for an HLSL file name, 0 for GLSL, -1 for neither (a --model text, another extension). */
static int language_of(const char *origin)
{
    const char *ext = strrchr(origin, '.');
    if (!ext || strchr(ext, '/'))
        return -1;
    if (strcmp(ext, ".hlsl") == 0 || strcmp(ext, ".fx") == 0 || strcmp(ext, ".fxh") == 0 || strcmp(ext, ".hlsli") == 0)
        return 1;
    if (strcmp(ext, ".glsl") == 0 || strcmp(ext, ".frag") == 0)
        return 0;
    return -1;
}

#ifdef BRDF_HAVE_GLSLANG
/* The defines as glslang's preamble: the command line's, then the header's it does not override. */
static void write_preamble(struct md_buf *pre, const struct header *h)
{
    for (int i = 0; i < cli_ndefines; ++i)
        md_printf(pre, "#define %s\n", cli_defines[i]);
    /* the command line's value wins over the header's (a header gives a default) */
    for (int i = 0; h && i < h->ndefines; ++i) {
        size_t nl = strcspn(h->defines[i], " ");
        int overridden = 0;
        for (int k = 0; k < cli_ndefines; ++k)
            if (strcspn(cli_defines[k], " ") == nl && strncmp(cli_defines[k], h->defines[i], nl) == 0)
                overridden = 1;
        if (!overridden)
            md_printf(pre, "#define %s\n", h->defines[i]);
    }
}

static void set_input(glslang_input_t *in, int hlsl, const char *code)
{
    memset(in, 0, sizeof *in);
    in->language = hlsl ? GLSLANG_SOURCE_HLSL : GLSLANG_SOURCE_GLSL;
    in->stage = GLSLANG_STAGE_FRAGMENT;
    in->client = GLSLANG_CLIENT_NONE;
    in->target_language = GLSLANG_TARGET_NONE;
    in->code = code;
    in->default_version = 450;
    in->default_profile = GLSLANG_NO_PROFILE;
    in->messages = GLSLANG_MSG_SUPPRESS_WARNINGS_BIT;
    in->resource = glslang_default_resource();
}

static void start_glslang(struct sl *S)
{
    static int initialised;
    if (!initialised) {
        if (!glslang_initialize_process())
            sl_fail_at(S, 0, 0, "glslang could not start");
        initialised = 1;
    }
}

/* glslang started, the header's preamble (its defines) in *pre and a NUL-terminated copy of the
   text to give it (malloc'd); out of memory is the model's error. */
static char *glslang_prepare(struct sl *S, const struct header *h, const char *text, size_t len, struct md_buf *pre)
{
    start_glslang(S);
    md_init(pre);
    write_preamble(pre, h);
    char *code = malloc(len + 1);
    if (!code || pre->failed) {
        free(code);
        md_free(pre);
        sl_fail_at(S, 0, 0, "out of memory");
    }
    memcpy(code, text, len);
    code[len] = '\0';
    return code;
}
#endif

/* The line of the text that a compiler numbers `logical` (#line N numbers the next line N), or 0. */
static int physical_line(const char *text, size_t len, int logical)
{
    int phys = 1, num = 1;
    for (size_t i = 0; i < len;) {
        if (num == logical)
            return phys;
        const char *eol = memchr(text + i, '\n', len - i);
        size_t e = eol ? (size_t)(eol - text) : len;
        size_t k = i;
        while (k < e && (text[k] == ' ' || text[k] == '\t'))
            ++k;
        int next_num = num + 1;
        if (k < e && text[k] == '#') {
            ++k;
            while (k < e && (text[k] == ' ' || text[k] == '\t'))
                ++k;
            if (e - k > 4 && strncmp(text + k, "line", 4) == 0 && (text[k + 4] == ' ' || text[k + 4] == '\t'))
                next_num = atoi(text + k + 5);
        }
        num = next_num;
        ++phys;
        i = e + 1;
    }
    return num == logical ? phys : 0;
}

void sl_validate(struct sl *S, const char *text, size_t len, int first_line, const struct header *h)
{
    int lang = language_of(S->origin);
#ifndef BRDF_HAVE_GLSLANG
    (void)text;
    (void)len;
    (void)first_line;
    (void)h;
    (void)lang;
#else
    if (lang < 0)
        return;
    struct md_buf pre;
    char *code = glslang_prepare(S, h, text, len, &pre);
    glslang_input_t in;
    set_input(&in, lang, code);
    glslang_shader_t *sh = glslang_shader_create(&in);
    char log[600] = "";
    int ok = 1;
    if (sh) {
        if (pre.len)
            glslang_shader_set_preamble(sh, pre.s);
        /* the C interface parses what its preprocessing step kept */
        ok = glslang_shader_preprocess(sh, &in) && glslang_shader_parse(sh, &in);
        if (!ok) {
            const char *l = glslang_shader_get_info_log(sh);
            snprintf(log, sizeof log, "%s", l ? l : "");
        }
        glslang_shader_delete(sh);
    }
    free(code);
    md_free(&pre);
    if (ok)
        return;
    /* "ERROR: 0:3: 'undefined_thing' : undeclared identifier": the line, the token, the message */
    const char *e = strstr(log, "ERROR: ");
    if (!e)
        sl_fail_at(S, 0, 0, "glslang refused the shader without a message");
    e += 7;
    int string_no = 0, line = 0, used = 0;
    if (!(sscanf(e, "%d:%d: %n", &string_no, &line, &used) >= 2 && used > 0))
        line = 0;
    e += used;
    const char *eol = strchr(e, '\n');
    int elen = eol ? (int)(eol - e) : (int)strlen(e);
    while (elen > 0 && isspace((unsigned char)e[elen - 1]))
        --elen;
    char tokbuf[80] = "";
    const char *msg = e;
    int mlen = elen;
    const char *sep = elen > 2 && e[0] == '\'' ? strstr(e, "' : ") : NULL;
    if (sep && sep - e < elen) {
        snprintf(tokbuf, sizeof tokbuf, "%.*s", (int)(sep - e - 1), e + 1);
        msg = sep + 4;
        mlen = elen - (int)(sep + 4 - e);
    }
    /* the column: the token looked for in the user's line, as a whole word (the text's own
       line, where a #line renumbered those after it) */
    int col = -1;
    int phys = physical_line(text, len, line);
    if (phys > 0 && tokbuf[0]) {
        const char *ls = text;
        for (int l = 1; l < phys && ls; ++l) {
            ls = memchr(ls, '\n', len - (size_t)(ls - text));
            ls = ls ? ls + 1 : NULL;
        }
        if (ls) {
            const char *le = memchr(ls, '\n', len - (size_t)(ls - text));
            if (!le)
                le = text + len;
            size_t tl = strlen(tokbuf);
            for (const char *p = ls; p + tl <= le; ++p)
                if (memcmp(p, tokbuf, tl) == 0 && !(p > ls && (isalnum((unsigned char)p[-1]) || p[-1] == '_')) &&
                    !(p + tl < le && (isalnum((unsigned char)p[tl]) || p[tl] == '_'))) {
                    col = (int)(p - ls) + 1;
                    break;
                }
        }
    }
    S->unknown_name = strstr(msg, "undeclared identifier") != NULL;
    if (tokbuf[0])
        sl_fail_at(S, line > 0 ? line + first_line - 1 : 0, col, "'%s': %.*s (glslang, the %s reference compiler)", tokbuf,
                   mlen, msg, lang ? "HLSL" : "GLSL");
    sl_fail_at(S, line > 0 ? line + first_line - 1 : 0, col, "%.*s (glslang, the %s reference compiler)", mlen, msg,
               lang ? "HLSL" : "GLSL");
#endif
}

const char *sl_preprocess(struct sl *S, const char *text, size_t len, int first_line, const struct header *h,
                          size_t *outlen)
{
    int first_directive = needs_preprocessor(S, text, len, first_line);
    int ndefines = cli_ndefines + (h ? h->ndefines : 0);
    if (!first_directive && ndefines == 0)
        return NULL;
#ifndef BRDF_HAVE_GLSLANG
    (void)outlen;
    sl_fail_at(S, first_directive ? first_directive + first_line - 1 : 0, -1,
               "this text needs a preprocessor (#if, #ifdef, function-like macros, defines), and brdfbench was "
               "built without glslang (Debian's glslang-dev; scripts/setup.sh installs it)");
#else
    struct md_buf pre;
    char *code = glslang_prepare(S, h, text, len, &pre);
    glslang_input_t in;
    set_input(&in, language_of(S->origin) == 1, code);
    glslang_shader_t *sh = glslang_shader_create(&in);
    if (!sh) {
        free(code);
        md_free(&pre);
        sl_fail_at(S, 0, 0, "glslang's preprocessor could not start");
    }
    if (pre.len)
        glslang_shader_set_preamble(sh, pre.s);
    int ok = glslang_shader_preprocess(sh, &in);
    const char *res = ok ? glslang_shader_get_preprocessed_code(sh) : NULL;
    char *kept = NULL;
    size_t klen = 0;
    char log[600] = "";
    if (res) {
        klen = strlen(res);
        kept = sl_arena_alloc(S, klen + 1);
        memcpy(kept, res, klen + 1);
    } else {
        const char *l = glslang_shader_get_info_log(sh);
        snprintf(log, sizeof log, "%s", l ? l : "");
    }
    glslang_shader_delete(sh);
    free(code);
    md_free(&pre);
    if (!kept)
        fail_from_log(S, log, first_line);
    /* the user's lines, for the columns (sl_pp_column) */
    struct sl_pp *pp = &S->pp;
    memset(pp, 0, sizeof *pp);
    pp->src = text;
    pp->src_len = len;
    pp->first_line = first_line;
    pp->cur_line = -1;
    int n = 1;
    for (size_t i = 0; i < len; ++i)
        n += text[i] == '\n';
    pp->line_start = sl_arena_alloc(S, sizeof *pp->line_start * (size_t)n);
    pp->nlines = n;
    n = 1;
    for (size_t i = 0; i < len; ++i)
        if (text[i] == '\n' && n < pp->nlines)
            pp->line_start[n++] = i + 1;
    *outlen = klen;
    return kept;
#endif
}
