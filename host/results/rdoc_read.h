/* rdoc_read.h - every result file with figures, read as rows (rdoc.h).
 *
 * One table names the kinds: their schema, file name and the older versions still read. One
 * function per kind turns its file's layout into rows, keys and metrics (with unit and
 * direction), so each layout is known here and nowhere else: compare, `gate --baseline`,
 * `plot` and `brdfbench rows` read results only through rdoc_read_file. A brdfbench.rows/1
 * document (what `brdfbench rows --format json` writes) is read back as the rows it holds.
 *
 * Before a figure is read the whole file is checked (compare_check.h): figures are numbers in
 * their range, labels one line of table-safe text. */
#ifndef BRDF_RDOC_READ_H
#define BRDF_RDOC_READ_H

#include <stddef.h>

#include "rdoc.h"

enum rd_kind { RD_KIND_THROUGHPUT = 0, RD_KIND_ACCURACY, RD_KIND_RENDER, RD_KIND_FIT, RD_KIND_FRONTIER, RD_KIND_COUNT };
const char *rd_kind_name(int kind);     /* "throughput", ... ("?" for another number) */
const char *rd_kind_file(int kind);     /* "throughput.json", ... */
const char *rd_kind_schema(int kind);   /* the version written now */
int rd_kind_of_name(const char *name);  /* the inverse of rd_kind_name; -1 for another */

/* Reads the result file at path (a regular file) into d. Returns 0, or 2 with a one-line
 * reason naming the file: unreadable, not strict JSON, a schema that is none of the kinds or
 * brdfbench.rows/1, an older version than the kind's table takes, a member out of its range. */
int rdoc_read_file(const char *path, struct rdoc *d, char *err, size_t errlen);

/* The kinds' files in a run folder (only the file of kind `only` when it is >= 0, no other
 * opened), read in the table's order into d[0..found); a missing file is skipped. Returns 0
 * with *found (0: none there), or 2 with a reason. */
int rdoc_read_folder(const char *dir, int only, struct rdoc d[RD_KIND_COUNT], int *found, char *err, size_t errlen);

#endif
