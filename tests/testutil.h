/* testutil.h - what the C tests share besides check.h: a temporary folder of the test's own,
 * made with mkdtemp and removed with everything in it at the end (kept when a check failed or
 * BRDF_KEEP_TEST_OUTPUT is set), a small input file written there and a file read back whole,
 * spec() for a model text the test needs parsed, and the opening and the end of the tests with
 * device checks (a skip when there is no OpenCL device). */
#ifndef BRDF_TEST_TESTUTIL_H
#define BRDF_TEST_TESTUTIL_H

#include "accuracy.h"
#include "check.h"
#include "clsession.h"
#include "exitcodes.h"
#include "models.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Makes dir = $TEST_TMPDIR (or $TMPDIR, or /tmp) / name_XXXXXX; -1 with a message on failure. */
static inline int test_tmpdir_make(char *dir, size_t len, const char *name)
{
    const char *base = getenv("TEST_TMPDIR");
    if (!base || !*base)
        base = getenv("TMPDIR");
    if (!base || !*base)
        base = "/tmp";
    if (snprintf(dir, len, "%s/%s_XXXXXX", base, name) >= (int)len || !mkdtemp(dir)) {
        perror("mkdtemp");
        return -1;
    }
    return 0;
}

/* Removes path and, for a folder, everything under it (links are removed, not followed). */
static inline int test_remove_tree(const char *path)
{
    struct stat st;
    if (lstat(path, &st) != 0)
        return -1;
    if (!S_ISDIR(st.st_mode))
        return unlink(path);
    DIR *d = opendir(path);
    if (!d)
        return -1;
    int rc = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        size_t n = strlen(path) + strlen(e->d_name) + 2;
        char *full = malloc(n);
        if (!full) {
            rc = -1;
            continue;
        }
        snprintf(full, n, "%s/%s", path, e->d_name);
        if (test_remove_tree(full) != 0)
            rc = -1;
        free(full);
    }
    closedir(d);
    return rmdir(path) != 0 ? -1 : rc;
}

/* The end of a test's folder: kept (and named) after a failed check or with
 * BRDF_KEEP_TEST_OUTPUT set, so that its files can be looked at; removed otherwise. */
static inline void test_tmpdir_done(const char *dir)
{
    if (check_failed || getenv("BRDF_KEEP_TEST_OUTPUT"))
        printf("test output kept in %s\n", dir);
    else if (test_remove_tree(dir) != 0)
        fprintf(stderr, "could not remove %s\n", dir);
}

/* Writes text to path; a test input that cannot be written ends the test (exit 3). */
static inline void test_write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (!f || fputs(text, f) == EOF || fclose(f) != 0) {
        perror(path);
        exit(3);
    }
}

/* A model spec such as "fq:Q=0.64"; a text the parser refuses ends the test (exit 3). */
static inline struct model_spec spec(const char *text)
{
    struct model_spec s;
    char err[256];
    if (model_spec_parse(text, &s, err, sizeof err) != 0) {
        fprintf(stderr, "cannot parse %s: %s\n", text, err);
        exit(3);
    }
    return s;
}

/* The whole of the file at path, NUL-terminated, its length in *len; NULL when it cannot be read. */
static inline char *test_read_file(const char *path, size_t *len)
{
    struct stat st;
    FILE *f = fopen(path, "rb");
    char *text = f && fstat(fileno(f), &st) == 0 ? malloc((size_t)st.st_size + 1) : NULL;
    size_t got = text ? fread(text, 1, (size_t)st.st_size, f) : 0;
    if (f)
        fclose(f);
    if (text && got == (size_t)st.st_size) {
        text[got] = '\0';
        *len = got;
        return text;
    }
    free(text);
    return NULL;
}

/* A test made of functions run in turn in a temporary folder of its own, dir (name_XXXXXX,
 * test_tmpdir_make): its exit status, 3 when the folder cannot be made. */
static inline int test_run_in_tmpdir(char *dir, size_t len, const char *name, void (*const tests[])(void),
                                     size_t count)
{
    if (test_tmpdir_make(dir, len, name) != 0)
        return 3;
    for (size_t i = 0; i < count; ++i)
        tests[i]();
    test_tmpdir_done(dir);
    return check_summary();
}

/* Opens a session on the first OpenCL device for a test's device checks and returns
 * clsession_open's code: 0 when open; EXIT_NO_DEVICE, with the reason printed, when there is no
 * device (the device checks are skipped); any other code is a failed check naming the error. */
static inline int test_session_open(struct cl_session *s)
{
    char err[512];
    int rc = clsession_open(s, -1, -1, err, sizeof err);
    if (rc == EXIT_NO_DEVICE)
        printf("no OpenCL device (%s): device checks skipped\n", err);
    else
        CHECK(rc == 0, "OpenCL session: %s", rc ? err : "");
    return rc;
}

/* The end of a test whose device checks needed the session test_session_open gave code rc:
 * a skip (77) when there was no device, unless a host check failed, which the skip must not
 * hide; the passed and failed checks otherwise. */
static inline int test_summary(int rc)
{
    return rc == EXIT_NO_DEVICE ? check_summary_skipped() : check_summary();
}

/* An accuracy test's device part and its end: body runs on the accuracy sweep of the first
 * OpenCL device (closed after it) and returns 0, or the code that stopped it, which fails the
 * test. The test's exit status, as test_summary gives it. */
static inline int test_accuracy_main(int (*body)(struct accuracy_ctx *a))
{
    struct cl_session s;
    int rc = test_session_open(&s);
    if (rc == 0) {
        struct accuracy_ctx a;
        if ((rc = accuracy_open(&a, &s, "")) == 0) {
            rc = body(&a);
            accuracy_close(&a);
        }
        clsession_close(&s);
        CHECK(rc == 0, "device checks ran (rc %d)", rc);
    }
    return test_summary(rc);
}

#endif
