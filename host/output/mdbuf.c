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
    for (; s && *s; s++) {
        if (*s == '|') md_printf(b, "\\|");
        else if (*s == '\n') md_printf(b, " ");
        else md_printf(b, "%c", *s);
    }
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
