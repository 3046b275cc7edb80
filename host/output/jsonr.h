/* jsonr.h - a small strict JSON reader (RFC 8259) for reading a run folder's results back.
 *
 * The whole text is parsed into a tree. Anything outside the standard is refused (comments,
 * trailing commas, single quotes, leading zeros, NaN literals, control characters in
 * strings, duplicate keys, text after the value), and every message names the file, the
 * line and column, and the problem. The typed getters name the file, the member and the
 * line of the object they looked in, so a reader of a result file reports e.g.
 * "run/plots.json:12:5: member \"n\" is missing". */
#ifndef BRDF_JSONR_H
#define BRDF_JSONR_H

#include <stddef.h>

enum jr_type { JR_NULL, JR_BOOL, JR_NUM, JR_STR, JR_ARR, JR_OBJ };

struct jr_value {
    enum jr_type type;
    int line, col;              /* where the value starts, 1-based */
    double num;                 /* JR_NUM; JR_BOOL: 0 or 1 */
    char *str;                  /* JR_STR: UTF-8, NUL-terminated (may hold no NUL itself) */
    size_t count;               /* JR_ARR / JR_OBJ: number of items */
    struct jr_value *items;     /* JR_ARR / JR_OBJ: the items */
    char **keys;                /* JR_OBJ: the members' names, parallel to items */
};

struct jr_doc {
    struct jr_value root;
    char name[512];             /* file name used in messages */
};

/* Parses a file. Returns 0, or 2 with a message when the file is missing, unreadable or
 * not strict JSON (then doc holds nothing to free). */
int jr_parse_file(const char *path, struct jr_doc *doc, char *err, size_t errlen);
/* The same with a size limit of max bytes, checked before the file is read. The file must be
 * a regular file (a FIFO or device is refused: host/output/infile.h). */
int jr_parse_file_max(const char *path, size_t max, struct jr_doc *doc, char *err, size_t errlen);
/* Parses text of length len; name is used in messages. Returns 0 or 2. */
int jr_parse_text(const char *text, size_t len, const char *name, struct jr_doc *doc, char *err, size_t errlen);
void jr_free(struct jr_doc *doc);

/* The member `key` of an object, or NULL (also when obj is not an object). */
const struct jr_value *jr_get(const struct jr_value *obj, const char *key);

/* Lenient access, for members a reader can do without: the string member `key` of obj, or dflt
 * when it is missing or not a string; the number member, or NAN (null reads as NAN too). */
const char *jr_str_or(const struct jr_value *obj, const char *key, const char *dflt);
double jr_num_or_nan(const struct jr_value *obj, const char *key);

/* Typed access with messages. Each returns 0, or 2 with "file:line:col: member \"key\" ..."
 * in err. A number member may be null (written for a non-finite value): it reads as NAN. */
int jr_need(const struct jr_doc *d, const struct jr_value *obj, const char *key, enum jr_type type,
            const struct jr_value **out, char *err, size_t errlen);
int jr_need_num(const struct jr_doc *d, const struct jr_value *obj, const char *key, double *out, char *err,
                size_t errlen);
int jr_need_str(const struct jr_doc *d, const struct jr_value *obj, const char *key, const char **out, char *err,
                size_t errlen);
/* An array member of numbers (null reads as NAN) copied into a malloc'd array. */
int jr_need_num_array(const struct jr_doc *d, const struct jr_value *obj, const char *key, double **out,
                      size_t *count, char *err, size_t errlen);
/* A message about value v: "file:line:col: <text>". Returns 2. */
int jr_fail(const struct jr_doc *d, const struct jr_value *v, char *err, size_t errlen, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

#endif
