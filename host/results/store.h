/* store.h - the store of runs: an SQLite database (results/history.sqlite by default) that
 * keeps each run's result documents (rdoc.h) with their context, so that `brdfbench history`
 * can read months of runs and CI jobs on several machines can put theirs in one place.
 *
 * Each stored document is one run of one kind (throughput, accuracy, ...): its rows document
 * (brdfbench.rows/1, as `rows --format json` writes it) kept whole, the context members a
 * listing and an ordering need (run date, commit, device, driver, build options, machine
 * load) as columns, and its figures once more as one table row per metric, for SQL readers.
 * A document is identified by a content hash of its rows document: adding the same run again
 * stores nothing new.
 *
 * Durability: the database is in WAL mode, every add is one transaction (BEGIN IMMEDIATE: a
 * second writer waits for the first, up to a busy timeout of 30 s, instead of failing), so
 * two CI jobs adding at once both land and a killed add leaves the store as it was. A file
 * that is not an SQLite database, one of another program (its application_id is not
 * brdfbench's), a newer layout or one that fails SQLite's quick_check is refused. */
#ifndef BRDF_STORE_H
#define BRDF_STORE_H

#include <stddef.h>

#include "rdoc.h"

#define STORE_DEFAULT_PATH "results/history.sqlite"
#define STORE_APPLICATION_ID 0x42524446   /* "BRDF" */
#define STORE_LAYOUT 1                    /* user_version of the layout written now */

struct store;

/* One stored document, as listed. */
struct store_run {
    long long id;
    char hash[33];               /* the content hash, 32 hex digits */
    char name[256];              /* what it was added as: the run folder's name or the file's path */
    char kind[32];
    char date[64];               /* the run's date (context "date") */
    char commit_date[64];        /* the commit's date where the context has one ("commit_date"), else "" */
    char commit[64];             /* context "git_revision" */
    char device[RD_TEXT];
    char driver[RD_TEXT];
    int nrows;
};

/* Opens the store at path. create: make the file when it is not there (store add); otherwise
 * a missing file is an error. Returns 0, EXIT_USAGE (2) for a file that is missing, not a
 * database, another program's or a newer layout, or EXIT_RUNTIME (3) for a database that
 * cannot be opened or fails its check; err has one line naming the file. */
int store_open(const char *path, int create, struct store **out, char *err, size_t errlen);
void store_close(struct store *s);

/* The content hash of a rows document's text: 32 hex digits (two independent 64-bit FNV-1a
 * hashes). */
void store_hash(const char *text, size_t len, char out[33]);

/* Adds the documents d[0..n) named names[i], in one transaction. added[i]: 1 when it was
 * new, 0 when a document with the same hash was there already. Returns 0, or EXIT_RUNTIME
 * with err (nothing of the call stored). */
int store_add(struct store *s, const struct rdoc *d, const char *const *names, int n, int *added, char *err,
              size_t errlen);

/* The stored documents (kind NULL: all), ordered by commit date where every one has one, else
 * by run date, then by id. *runs is malloc'd. Returns 0 or EXIT_RUNTIME. */
int store_list(struct store *s, const char *kind, struct store_run **runs, int *n, char *err, size_t errlen);

/* The rows document of stored run id read back into d. Returns 0, or EXIT_RUNTIME (a document
 * that does not read back: the store was written to by another program). */
int store_read(struct store *s, long long id, struct rdoc *d, char *err, size_t errlen);
/* Its text, malloc'd. */
int store_text(struct store *s, long long id, char **text, char *err, size_t errlen);

#endif
