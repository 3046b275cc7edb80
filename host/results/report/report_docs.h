/* report_docs.h - the rows of a run folder's result files, read once for report.md (implemented in
 * report.c): every section of the page is drawn from them (and from run.json), never from a file's
 * own layout or from a page an engine wrote. A page an engine writes beside its JSON (claims.md,
 * throughput.md, ...) is made by the same function of the same rows, so the two agree. */
#ifndef BRDF_REPORT_DOCS_H
#define BRDF_REPORT_DOCS_H

#include <stddef.h>

#include "rdoc.h"

#define REPORT_DOCS_MAX 16

struct report_docs {
    const char *run_dir;
    int count;
    char file[REPORT_DOCS_MAX][64];
    int state[REPORT_DOCS_MAX];        /* 0 read, 1 not there, 2 unreadable */
    char why[REPORT_DOCS_MAX][512];    /* the message of state 2 */
    struct rdoc doc[REPORT_DOCS_MAX];
};

void report_docs_init(struct report_docs *docs, const char *run_dir);
void report_docs_free(struct report_docs *docs);
/* The rows of run_dir/file (rdoc_read_file: the rows it carries, or its previous version's
 * layout through the upgrade functions), read on the first call and kept. NULL when the file is
 * not there (*rc = 1, err "FOLDER/FILE: missing") or cannot be read (*rc = 2, err the reader's
 * message naming the file); else *rc = 0. */
const struct rdoc *report_doc(struct report_docs *docs, const char *file, int *rc, char *err, size_t errlen);
/* Rows a run holds in memory for file (`all`: the rows an engine built and wrote as the file's rows
 * member), so that report_doc gives them instead of reading the file back. The rows must be the
 * ones the file carries (what rdoc_read_file would give), so that report.md from memory and
 * `brdfbench report RUN` from the files are the same page. *rdoc moves into docs (which frees
 * it; *rdoc is left empty). 0, or -1 with a message when file is already there or docs is full
 * (*rdoc is then freed). */
int report_docs_put(struct report_docs *docs, const char *file, struct rdoc *rdoc, char *err, size_t errlen);

#endif
