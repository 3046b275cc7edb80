/* report_docs.c - the run folder's rows for report.md (report_docs.h). */
#include "report_docs.h"

#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "outdir.h"
#include "rdoc_read.h"

void report_docs_init(struct report_docs *docs, const char *run_dir)
{
    memset(docs, 0, sizeof *docs);
    docs->run_dir = run_dir;
}

void report_docs_free(struct report_docs *docs)
{
    for (int i = 0; i < docs->count; ++i)
        if (docs->state[i] == 0)
            rdoc_free(&docs->doc[i]);
    docs->count = 0;
}

const struct rdoc *report_doc(struct report_docs *docs, const char *file, int *rc, char *err, size_t errlen)
{
    int i = 0;
    while (i < docs->count && strcmp(docs->file[i], file) != 0)
        ++i;
    if (i == docs->count) {
        if (docs->count == REPORT_DOCS_MAX) {
            snprintf(err, errlen, "%s/%s: more result files than the report reads (%d)", docs->run_dir, file,
                     REPORT_DOCS_MAX);
            *rc = 2;
            return NULL;
        }
        snprintf(docs->file[i], sizeof docs->file[i], "%s", file);
        docs->count++;
        char path[4200];
        struct stat st;
        if (path_join(path, sizeof path, docs->run_dir, file)) {
            snprintf(docs->why[i], sizeof docs->why[i], "%s/%s: path too long", docs->run_dir, file);
            docs->state[i] = 2;
        } else if (stat(path, &st) != 0) {
            snprintf(docs->why[i], sizeof docs->why[i], "%s/%s: missing", docs->run_dir, file);
            docs->state[i] = 1;
        } else {
            docs->state[i] = rdoc_read_file(path, &docs->doc[i], docs->why[i], sizeof docs->why[i]) ? 2 : 0;
        }
    }
    *rc = docs->state[i];
    if (*rc) {
        snprintf(err, errlen, "%s", docs->why[i]);
        return NULL;
    }
    return &docs->doc[i];
}

int report_docs_put(struct report_docs *docs, const char *file, struct rdoc *rdoc, char *err, size_t errlen)
{
    int i = 0;
    while (i < docs->count && strcmp(docs->file[i], file) != 0)
        ++i;
    if (i < docs->count || docs->count == REPORT_DOCS_MAX || strlen(file) >= sizeof docs->file[0]) {
        snprintf(err, errlen, "%s: %s", file,
                 i < docs->count ? "already among the report's rows" : "more result files than the report reads");
        rdoc_free(rdoc);
        memset(rdoc, 0, sizeof *rdoc);
        return -1;
    }
    snprintf(docs->file[i], sizeof docs->file[i], "%s", file);
    docs->state[i] = 0;
    docs->why[i][0] = '\0';
    docs->doc[i] = *rdoc;   /* moved: its rows and texts are docs' now */
    memset(rdoc, 0, sizeof *rdoc);
    docs->count++;
    return 0;
}
