/* rdoc_read.h - every result file with figures, read as rows (rdoc.h).
 *
 * One table names the kinds: their schema and file name. A file of the version written now
 * carries its rows (its "rows" member, made by the engine where it measures: rdoc.h) and is read
 * by them, as a brdfbench.rows/1 document (what `brdfbench rows --format json` writes) is; a
 * file of a previous version is turned into the same rows by the upgrade function of its
 * schema, and accuracy.json, which carries no rows yet, by its layout. compare,
 * `gate --baseline`, `plot` and `brdfbench rows` read results only through rdoc_read_file.
 *
 * Before a figure is read the whole file is checked (compare_check.h): figures are numbers in
 * their range, labels one line of table-safe text. */
#ifndef BRDF_RDOC_READ_H
#define BRDF_RDOC_READ_H

#include <stddef.h>

#include "rdoc.h"

enum rd_kind { RD_KIND_THROUGHPUT = 0, RD_KIND_ACCURACY, RD_KIND_RENDER, RD_KIND_FIT, RD_KIND_FRONTIER,
               RD_KIND_CLAIMS, RD_KIND_Q_SWEEP, RD_KIND_PHYSICAL, RD_KIND_ENERGY, RD_KIND_MEASURED, RD_KIND_FIELD,
               RD_KIND_FIT_FAMILY,
               RD_KIND_COUNT };
const char *rd_kind_name(int kind);     /* "throughput", ... ("?" for another number) */
const char *rd_kind_file(int kind);     /* "throughput.json", ... */
const char *rd_kind_schema(int kind);   /* the version written now */
int rd_kind_of_name(const char *name);  /* the inverse of rd_kind_name; -1 for another */
/* Every kind's name, "throughput, accuracy, ...", into out (a message's accepted list). */
void rd_kind_names(char *out, size_t len);
/* The files a run folder's rows are read from ("throughput.json, accuracy.json, ..."), each once. */
void rd_kind_files(char *out, size_t len);

/* Reads the result file at path (a regular file) into d. Returns 0, or 2 with a one-line
 * reason naming the file: unreadable, not strict JSON, a schema that is none of the kinds or
 * brdfbench.rows/1, a version this one does not read, a current file without its rows, a member
 * out of its range. */
int rdoc_read_file(const char *path, struct rdoc *d, char *err, size_t errlen);

/* The kinds' files in a run folder (only the file of kind `only` when it is >= 0, no other
 * opened), read in the table's order into d[0..found); a missing file is skipped. Returns 0
 * with *found (0: none there), or 2 with a reason. */
int rdoc_read_folder(const char *dir, int only, struct rdoc d[RD_KIND_COUNT], int *found, char *err, size_t errlen);

#endif
