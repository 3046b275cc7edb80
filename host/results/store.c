/* store.c - the SQLite store of runs (see store.h). */
#include "store.h"

#include <errno.h>
#include <sqlite3.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "exitcodes.h"
#include "jsonr.h"
#include "mdbuf.h"

struct store {
    sqlite3 *db;
    char path[1024];
};

/* The layout. runs: one stored document each; metrics: its figures, one line per metric of a
 * row, for SQL readers (history reads the documents). */
static const char *const layout_sql =
    "CREATE TABLE runs ("
    " id INTEGER PRIMARY KEY,"
    " hash TEXT NOT NULL UNIQUE,"
    " name TEXT NOT NULL,"
    " kind TEXT NOT NULL,"
    " run_date TEXT NOT NULL,"
    " commit_date TEXT NOT NULL,"
    " git_revision TEXT NOT NULL,"
    " device TEXT NOT NULL,"
    " driver TEXT NOT NULL,"
    " build_options TEXT NOT NULL,"
    " machine TEXT NOT NULL,"
    " nrows INTEGER NOT NULL,"
    " added TEXT NOT NULL,"
    " document TEXT NOT NULL);"
    "CREATE TABLE metrics ("
    " run_id INTEGER NOT NULL REFERENCES runs(id) ON DELETE CASCADE,"
    " device TEXT NOT NULL,"
    " row TEXT NOT NULL,"
    " status TEXT NOT NULL,"
    " metric TEXT NOT NULL,"
    " unit TEXT NOT NULL,"
    " direction TEXT NOT NULL,"
    " value REAL,"
    " min REAL,"
    " max REAL,"
    " nreps INTEGER NOT NULL);"
    "CREATE INDEX metrics_run ON metrics(run_id);";

static int fail(char *err, size_t errlen, int code, const char *fmt, const char *a, const char *b)
{
    snprintf(err, errlen, fmt, a, b);
    return code;
}

/* The 64-bit FNV-1a hash of text from a given offset basis. */
static uint64_t fnv1a(const char *s, size_t n, uint64_t h)
{
    for (size_t i = 0; i < n; ++i) {
        h ^= (unsigned char)s[i];
        h *= 0x100000001b3ULL;
    }
    return h;
}

void store_hash(const char *text, size_t len, char out[33])
{
    /* two offset bases: FNV's own and another odd constant; 128 bits in all */
    uint64_t a = fnv1a(text, len, 0xcbf29ce484222325ULL), b = fnv1a(text, len, 0x9e3779b97f4a7c15ULL);
    snprintf(out, 33, "%016llx%016llx", (unsigned long long)a, (unsigned long long)b);
}

static int exec(struct store *s, const char *sql, char *err, size_t errlen)
{
    char *msg = NULL;
    if (sqlite3_exec(s->db, sql, NULL, NULL, &msg) != SQLITE_OK) {
        snprintf(err, errlen, "%s: %s", s->path, msg ? msg : sqlite3_errmsg(s->db));
        sqlite3_free(msg);
        return EXIT_RUNTIME;
    }
    return 0;
}

/* One integer of a PRAGMA, or -1. */
static long long pragma_int(struct store *s, const char *sql, int *rc)
{
    sqlite3_stmt *st = NULL;
    long long v = -1;
    *rc = sqlite3_prepare_v2(s->db, sql, -1, &st, NULL);
    if (*rc == SQLITE_OK) {
        *rc = sqlite3_step(st);
        if (*rc == SQLITE_ROW) {
            v = sqlite3_column_int64(st, 0);
            *rc = SQLITE_OK;
        }
    }
    sqlite3_finalize(st);
    return v;
}

/* Checks an existing database is brdfbench's store, or makes the layout in an empty one. */
static int check_or_init(struct store *s, char *err, size_t errlen)
{
    int rc;
    long long app = pragma_int(s, "PRAGMA application_id", &rc);
    if (rc == SQLITE_NOTADB)
        return fail(err, errlen, EXIT_USAGE, "%s: not an SQLite database (%s); a store is made by brdfbench store add",
                    s->path, "file is not a database");
    if (rc != SQLITE_OK)
        return fail(err, errlen, EXIT_RUNTIME, "%s: cannot read the database: %s", s->path, sqlite3_errmsg(s->db));
    long long tables = pragma_int(s, "SELECT count(*) FROM sqlite_master", &rc);
    if (rc != SQLITE_OK)
        return fail(err, errlen, EXIT_RUNTIME, "%s: cannot read the database: %s", s->path, sqlite3_errmsg(s->db));
    if (app == 0 && tables == 0) {   /* a new (empty) database: brdfbench's layout, in one transaction */
        if (exec(s, "BEGIN IMMEDIATE", err, errlen))
            return EXIT_RUNTIME;
        /* another writer may have made it between the look and the lock */
        app = pragma_int(s, "PRAGMA application_id", &rc);
        if (app == 0) {
            char sql[2600];
            snprintf(sql, sizeof sql, "%sPRAGMA application_id = %d; PRAGMA user_version = %d;", layout_sql,
                     STORE_APPLICATION_ID, STORE_LAYOUT);
            if (exec(s, sql, err, errlen)) {
                sqlite3_exec(s->db, "ROLLBACK", NULL, NULL, NULL);
                return EXIT_RUNTIME;
            }
        }
        return exec(s, "COMMIT", err, errlen);
    }
    if (app != STORE_APPLICATION_ID) {
        char got[32];
        snprintf(got, sizeof got, "0x%llx", (unsigned long long)app);
        return fail(err, errlen, EXIT_USAGE,
                    "%s: an SQLite database of another program (application_id %s, a brdfbench store has 0x42524446)",
                    s->path, got);
    }
    long long layout = pragma_int(s, "PRAGMA user_version", &rc);
    if (layout != STORE_LAYOUT) {
        char got[64];
        snprintf(got, sizeof got, "%lld, this brdfbench reads %d", layout, STORE_LAYOUT);
        return fail(err, errlen, EXIT_USAGE, "%s: a store of another layout (version %s)", s->path, got);
    }
    sqlite3_stmt *st = NULL;
    int ok = 0;
    if (sqlite3_prepare_v2(s->db, "PRAGMA quick_check", -1, &st, NULL) == SQLITE_OK && sqlite3_step(st) == SQLITE_ROW) {
        const char *r = (const char *)sqlite3_column_text(st, 0);
        ok = r && strcmp(r, "ok") == 0;
    }
    char why[200];
    snprintf(why, sizeof why, "%s", ok ? "" : sqlite3_errmsg(s->db));
    sqlite3_finalize(st);
    if (!ok)
        return fail(err, errlen, EXIT_RUNTIME, "%s: the database is damaged (SQLite's quick_check fails: %s)", s->path,
                    why);
    return 0;
}

int store_open(const char *path, int create, struct store **out, char *err, size_t errlen)
{
    *out = NULL;
    struct stat st;
    if (stat(path, &st) != 0) {
        if (!create)
            return fail(err, errlen, EXIT_USAGE, "%s: no such store (%s; brdfbench store add makes one)", path,
                        strerror(errno));
    } else if (!S_ISREG(st.st_mode)) {
        return fail(err, errlen, EXIT_USAGE, "%s: not a regular file (%s)", path, "a store is an SQLite file");
    }
    struct store *s = calloc(1, sizeof *s);
    if (!s)
        return fail(err, errlen, EXIT_RUNTIME, "%s: %s", path, "out of memory");
    snprintf(s->path, sizeof s->path, "%s", path);
    int flags = SQLITE_OPEN_READWRITE | (create ? SQLITE_OPEN_CREATE : 0) | SQLITE_OPEN_NOFOLLOW;
    int rc = sqlite3_open_v2(path, &s->db, flags, NULL);
    if (rc != SQLITE_OK) {
        fail(err, errlen, rc == SQLITE_CANTOPEN ? EXIT_USAGE : EXIT_RUNTIME, "%s: cannot open the store: %s", path,
             s->db ? sqlite3_errmsg(s->db) : "out of memory");
        store_close(s);
        return rc == SQLITE_CANTOPEN ? EXIT_USAGE : EXIT_RUNTIME;
    }
    sqlite3_busy_timeout(s->db, 30000);   /* a second writer waits for the first */
    int code = check_or_init(s, err, errlen);
    /* WAL: readers do not block the writer; synchronous NORMAL is durable across a process
       kill in WAL mode (a power loss may lose the last transaction, never corrupt) */
    if (!code)
        code = exec(s, "PRAGMA journal_mode = WAL; PRAGMA synchronous = NORMAL; PRAGMA foreign_keys = ON;", err, errlen);
    if (code) {
        store_close(s);
        return code;
    }
    *out = s;
    return 0;
}

void store_close(struct store *s)
{
    if (!s)
        return;
    sqlite3_close(s->db);
    free(s);
}

static void bind_text(sqlite3_stmt *st, int i, const char *v) { sqlite3_bind_text(st, i, v ? v : "", -1, SQLITE_TRANSIENT); }

static void bind_real(sqlite3_stmt *st, int i, double v)
{
    if (v == v && v - v == 0)   /* finite */
        sqlite3_bind_double(st, i, v);
    else
        sqlite3_bind_null(st, i);
}

/* Inserts one document (inside the caller's transaction). *added: 1 new, 0 there already. */
static int add_one(struct store *s, const struct rdoc *d, const char *name, int *added, char *err, size_t errlen)
{
    struct md_buf b;
    md_init(&b);
    rdoc_json(d, &b);
    if (b.failed) {
        md_free(&b);
        return fail(err, errlen, EXIT_RUNTIME, "%s: %s", name, "out of memory");
    }
    char hash[33], now[32];
    store_hash(b.s, b.len, hash);
    time_t t = time(NULL);
    struct tm tm;
    gmtime_r(&t, &tm);
    strftime(now, sizeof now, "%Y-%m-%dT%H:%M:%SZ", &tm);
    static const char *const ctx_cols[] = { "date", "commit_date", "git_revision", "device", "driver_version",
                                            "build_options", "machine" };
    sqlite3_stmt *st = NULL;
    int code = 0;
    if (sqlite3_prepare_v2(s->db,
                           "INSERT OR IGNORE INTO runs(hash, name, kind, run_date, commit_date, git_revision, device, "
                           "driver, build_options, machine, nrows, added, document) "
                           "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13)",
                           -1, &st, NULL) != SQLITE_OK)
        goto sqlfail;
    bind_text(st, 1, hash);
    bind_text(st, 2, name);
    bind_text(st, 3, d->kind);
    for (int c = 0; c < 7; ++c)
        bind_text(st, 4 + c, rd_ctx_get(&d->ctx, ctx_cols[c]));
    sqlite3_bind_int(st, 11, d->nrows);
    bind_text(st, 12, now);
    sqlite3_bind_text(st, 13, b.s, (int)b.len, SQLITE_TRANSIENT);
    if (sqlite3_step(st) != SQLITE_DONE)
        goto sqlfail;
    *added = sqlite3_changes(s->db) > 0;
    sqlite3_finalize(st);
    st = NULL;
    if (*added) {
        long long id = sqlite3_last_insert_rowid(s->db);
        if (sqlite3_prepare_v2(s->db,
                               "INSERT INTO metrics(run_id, device, row, status, metric, unit, direction, value, min, "
                               "max, nreps) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11)",
                               -1, &st, NULL) != SQLITE_OK)
            goto sqlfail;
        for (int i = 0; i < d->nrows; ++i) {
            const struct rd_row *r = &d->rows[i];
            for (int m = 0; m < r->nmetrics; ++m) {
                const struct rd_metric *x = &r->metrics[m];
                sqlite3_reset(st);
                sqlite3_bind_int64(st, 1, id);
                bind_text(st, 2, r->device);
                bind_text(st, 3, r->label);
                bind_text(st, 4, r->status);
                bind_text(st, 5, x->name);
                bind_text(st, 6, x->unit);
                bind_text(st, 7, rd_direction_name(x->direction));
                bind_real(st, 8, x->value);
                bind_real(st, 9, x->lo);
                bind_real(st, 10, x->hi);
                sqlite3_bind_int(st, 11, x->nreps);
                if (sqlite3_step(st) != SQLITE_DONE)
                    goto sqlfail;
            }
        }
    }
    goto done;
sqlfail:
    code = fail(err, errlen, EXIT_RUNTIME, "%s: cannot store the run: %s", s->path, sqlite3_errmsg(s->db));
done:
    sqlite3_finalize(st);
    md_free(&b);
    return code;
}

int store_add(struct store *s, const struct rdoc *d, const char *const *names, int n, int *added, char *err,
              size_t errlen)
{
    /* IMMEDIATE: the write lock is taken now, so a second writer waits here (busy timeout)
       rather than failing at its first insert */
    if (exec(s, "BEGIN IMMEDIATE", err, errlen))
        return EXIT_RUNTIME;
    for (int i = 0; i < n; ++i)
        if (add_one(s, &d[i], names[i], &added[i], err, errlen)) {
            sqlite3_exec(s->db, "ROLLBACK", NULL, NULL, NULL);
            return EXIT_RUNTIME;
        }
    if (exec(s, "COMMIT", err, errlen)) {
        sqlite3_exec(s->db, "ROLLBACK", NULL, NULL, NULL);
        return EXIT_RUNTIME;
    }
    return 0;
}

static void col_text(sqlite3_stmt *st, int c, char *out, size_t len)
{
    const unsigned char *t = sqlite3_column_text(st, c);
    snprintf(out, len, "%s", t ? (const char *)t : "");
}

int store_list(struct store *s, const char *kind, struct store_run **runs, int *n, char *err, size_t errlen)
{
    *runs = NULL;
    *n = 0;
    int rc;
    /* commit order where every document has a commit date, else run order */
    char count_sql[200];
    snprintf(count_sql, sizeof count_sql, "SELECT count(*) FROM runs WHERE commit_date = ''%s",
             kind ? " AND kind = ?1" : "");
    sqlite3_stmt *st = NULL;
    long long undated = 0;
    if (sqlite3_prepare_v2(s->db, count_sql, -1, &st, NULL) == SQLITE_OK) {
        if (kind)
            bind_text(st, 1, kind);
        if (sqlite3_step(st) == SQLITE_ROW)
            undated = sqlite3_column_int64(st, 0);
    }
    sqlite3_finalize(st);
    st = NULL;
    char sql[400];
    snprintf(sql, sizeof sql,
             "SELECT id, hash, name, kind, run_date, commit_date, git_revision, device, driver, nrows FROM runs%s "
             "ORDER BY %s, id",
             kind ? " WHERE kind = ?1" : "", undated ? "run_date" : "commit_date, run_date");
    if (sqlite3_prepare_v2(s->db, sql, -1, &st, NULL) != SQLITE_OK)
        return fail(err, errlen, EXIT_RUNTIME, "%s: %s", s->path, sqlite3_errmsg(s->db));
    if (kind)
        bind_text(st, 1, kind);
    int cap = 0;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
        if (*n == cap) {
            cap = cap ? 2 * cap : 16;
            struct store_run *g = realloc(*runs, (size_t)cap * sizeof *g);
            if (!g) {
                sqlite3_finalize(st);
                return fail(err, errlen, EXIT_RUNTIME, "%s: %s", s->path, "out of memory");
            }
            *runs = g;
        }
        struct store_run *r = &(*runs)[(*n)++];
        memset(r, 0, sizeof *r);
        r->id = sqlite3_column_int64(st, 0);
        col_text(st, 1, r->hash, sizeof r->hash);
        col_text(st, 2, r->name, sizeof r->name);
        col_text(st, 3, r->kind, sizeof r->kind);
        col_text(st, 4, r->date, sizeof r->date);
        col_text(st, 5, r->commit_date, sizeof r->commit_date);
        col_text(st, 6, r->commit, sizeof r->commit);
        col_text(st, 7, r->device, sizeof r->device);
        col_text(st, 8, r->driver, sizeof r->driver);
        r->nrows = sqlite3_column_int(st, 9);
    }
    sqlite3_finalize(st);
    if (rc != SQLITE_DONE)
        return fail(err, errlen, EXIT_RUNTIME, "%s: %s", s->path, sqlite3_errmsg(s->db));
    return 0;
}

int store_text(struct store *s, long long id, char **text, char *err, size_t errlen)
{
    *text = NULL;
    sqlite3_stmt *st = NULL;
    int code = 0;
    if (sqlite3_prepare_v2(s->db, "SELECT document FROM runs WHERE id = ?1", -1, &st, NULL) != SQLITE_OK)
        return fail(err, errlen, EXIT_RUNTIME, "%s: %s", s->path, sqlite3_errmsg(s->db));
    sqlite3_bind_int64(st, 1, id);
    if (sqlite3_step(st) == SQLITE_ROW) {
        const char *t = (const char *)sqlite3_column_text(st, 0);
        *text = t ? strdup(t) : NULL;
        if (!*text)
            code = fail(err, errlen, EXIT_RUNTIME, "%s: %s", s->path, "out of memory or an empty document");
    } else {
        code = fail(err, errlen, EXIT_RUNTIME, "%s: %s", s->path, "no such stored run");
    }
    sqlite3_finalize(st);
    return code;
}

int store_read(struct store *s, long long id, struct rdoc *d, char *err, size_t errlen)
{
    char *text = NULL;
    int code = store_text(s, id, &text, err, errlen);
    if (code)
        return code;
    char name[1100];
    snprintf(name, sizeof name, "%s#%lld", s->path, id);
    struct jr_doc j;
    if (jr_parse_text(text, strlen(text), name, &j, err, errlen)) {
        free(text);
        return EXIT_RUNTIME;
    }
    code = rdoc_from_rows_json(&j, d, err, errlen) ? EXIT_RUNTIME : 0;
    jr_free(&j);
    free(text);
    return code;
}
