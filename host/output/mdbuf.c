/* mdbuf.c - the growable text buffer (see mdbuf.h). */
#include "mdbuf.h"
#include "outdir.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void md_init(struct md_buf *b) { memset(b, 0, sizeof *b); }

void md_free(struct md_buf *b)
{
    free(b->s);
    memset(b, 0, sizeof *b);
}

/* Room for `need` bytes in all (the NUL included); 0, or -1 with `failed` set. */
static int md_reserve(struct md_buf *b, size_t need)
{
    if (need <= b->cap)
        return 0;
    size_t nc = b->cap ? b->cap : 4096;
    while (nc < need)
        nc *= 2;
    char *ns = realloc(b->s, nc);
    if (!ns) {
        b->failed = 1;
        return -1;
    }
    b->s = ns;
    b->cap = nc;
    return 0;
}

void md_printf(struct md_buf *b, const char *fmt, ...)
{
    if (b->failed) return;
    for (;;) {
        size_t room = b->cap - b->len;
        va_list ap;
        va_start(ap, fmt);
        int n = b->s ? vsnprintf(b->s + b->len, room, fmt, ap) : -2;
        va_end(ap);
        if (n >= 0 && (size_t)n < room) {
            b->len += (size_t)n;
            return;
        }
        if (n == -1) {
            b->failed = 1;
            return;
        }
        if (md_reserve(b, b->len + (n > 0 ? (size_t)n : 0) + 1))
            return;
    }
}

void md_append(struct md_buf *b, const char *text, size_t n)
{
    if (b->failed || md_reserve(b, b->len + n + 1))
        return;
    memcpy(b->s + b->len, text, n);
    b->len += n;
    b->s[b->len] = '\0';
}

void md_csv_text(struct md_buf *b, const char *s)
{
    md_append(b, "\"", 1);
    for (; s && *s; s++)
        md_append(b, *s == '"' ? "\"\"" : s, *s == '"' ? 2 : 1);
    md_append(b, "\"", 1);
}

void md_cell_text(struct md_buf *b, const char *s)
{
    /* HTML's own characters as entities (a file name "<img onerror=...>" stays text), control
       characters (newlines, ESC) as spaces */
    for (; s && *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '|') md_printf(b, "\\|");
        else if (c < 0x20 || c == 0x7f) md_printf(b, " ");
        else if (c == '<') md_printf(b, "&lt;");
        else if (c == '>') md_printf(b, "&gt;");
        else if (c == '&') md_printf(b, "&amp;");
        else md_printf(b, "%c", *s);
    }
}

void md_text(struct md_buf *b, const char *s)
{
    for (; s && *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c < 0x20 || c == 0x7f) md_printf(b, " ");
        else if (c == '<') md_printf(b, "&lt;");
        else if (c == '>') md_printf(b, "&gt;");
        else if (c == '&') md_printf(b, "&amp;");
        else if (strchr("\\`*_[]#!|{}", c)) md_printf(b, "\\%c", c);
        else md_printf(b, "%c", *s);
    }
}

void md_code(struct md_buf *b, const char *s)
{
    /* a fence one backtick longer than the longest run inside; a space pads a text that
       begins or ends with a backtick */
    int longest = 0, run = 0;
    size_t n = s ? strlen(s) : 0;
    for (size_t i = 0; i < n; ++i) {
        run = s[i] == '`' ? run + 1 : 0;
        if (run > longest) longest = run;
    }
    char fence[16];
    int f = longest + 1 < (int)sizeof fence - 1 ? longest + 1 : (int)sizeof fence - 1;
    memset(fence, '`', (size_t)f);
    fence[f] = '\0';
    int pad = n && (s[0] == '`' || s[n - 1] == '`');
    md_printf(b, "%s%s", fence, pad ? " " : "");
    for (size_t i = 0; i < n; ++i) {
        unsigned char c = (unsigned char)s[i];
        md_printf(b, "%c", c < 0x20 || c == 0x7f ? ' ' : s[i]);
    }
    md_printf(b, "%s%s", pad ? " " : "", fence);
}

void md_embed(struct md_buf *b, const char *page)
{
    const char *p = page;
    if (p[0] == '#' && p[1] == ' ') { /* the page's own title */
        const char *nl = strchr(p, '\n');
        p = nl ? nl + 1 : p + strlen(p);
    }
    while (*p) {
        const char *nl = strchr(p, '\n');
        size_t len = nl ? (size_t)(nl - p) : strlen(p);
        if (p[0] == '#') md_printf(b, "#");
        md_printf(b, "%.*s\n", (int)len, p);
        p += len + (nl ? 1 : 0);
    }
}

int md_write_file_free(struct md_buf *b, const char *path, char *err, size_t errlen)
{
    int rc = b->failed ? -1 : write_file_atomic(path, b->s ? b->s : "", b->len, err, errlen);
    if (b->failed) snprintf(err, errlen, "%s: out of memory", path);
    md_free(b);
    return rc;
}

void str_appendf(char **out, size_t *len, const char *fmt, ...)
{
    if (!out)
        return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0)
        return;
    char *s = realloc(*out, *len + (size_t)n + 1);
    if (!s)
        return;
    va_start(ap, fmt);
    vsnprintf(s + *len, (size_t)n + 1, fmt, ap);
    va_end(ap);
    *out = s;
    *len += (size_t)n;
}
