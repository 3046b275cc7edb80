/* mdbuf.h - a growable NUL-terminated text buffer: markdown blocks, CSV and XML files, and
 * kernel source are built in it before being written in one piece. An allocation failure sets
 * `failed`; later calls do nothing, so a caller checks once at the end. */
#ifndef BRDF_MDBUF_H
#define BRDF_MDBUF_H

#include <stddef.h>

struct md_buf {
    char *s;        /* NULL until the first text; NUL-terminated after it */
    size_t len, cap;
    int failed;
};
void md_init(struct md_buf *b);
/* Appends formatted text, whatever its length. */
void md_printf(struct md_buf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Appends formatted text to a malloc'd string *out of *len bytes (NULL and 0 at first; out NULL:
 * nothing), whatever its length; on an allocation failure the string stays as it was. For the
 * messages that are handed back as a plain string (compare's and history's --fail-if-slower). */
void str_appendf(char **out, size_t *len, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* Appends n bytes of text as they are. */
void md_append(struct md_buf *b, const char *text, size_t n);
/* Text for a markdown table cell: '|' escaped, '<', '>', '&' as HTML entities, control
 * characters (line breaks, ESC) as spaces (NULL: nothing). */
void md_cell_text(struct md_buf *b, const char *s);
/* Text a file or a name brings, as plain text in a markdown paragraph or heading: markdown's
 * own characters (\ ` * _ [ ] # ! | { }) backslash-escaped, HTML's as entities, control
 * characters as spaces. */
void md_text(struct md_buf *b, const char *s);
/* The same as inline code: in backticks (more of them than any run inside), control
 * characters as spaces; nothing in it is markdown or HTML. */
void md_code(struct md_buf *b, const char *s);
/* Appends a markdown page as a section of another: its title line (# ...) is dropped and
 * every other heading goes one level down. */
void md_embed(struct md_buf *b, const char *page);
/* A CSV field (RFC 4180): the text in double quotes, each '"' in it doubled (NULL: ""). */
void md_csv_text(struct md_buf *b, const char *s);
void md_free(struct md_buf *b);
/* The text written to path by write_file_atomic (outdir.h), then the buffer freed; a buffer
 * that ran out of memory is not written ("PATH: out of memory"). Returns 0 or -1. */
int md_write_file_free(struct md_buf *b, const char *path, char *err, size_t errlen);

#endif
