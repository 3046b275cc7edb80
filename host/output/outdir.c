/* outdir.c - atomic writes, output folders and run folders. */
#define _POSIX_C_SOURCE 200809L
#include "outdir.h"

#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

int path_join(char *out, size_t outlen, const char *dir, const char *name)
{
    int n = snprintf(out, outlen, "%s/%s", dir, name);
    return (n < 0 || (size_t)n >= outlen) ? -1 : 0;
}

int write_file_atomic(const char *path, const void *data, size_t len, char *err, size_t errlen)
{
    char tmp[4096];
    if (snprintf(tmp, sizeof tmp, "%s.tmp.XXXXXX", path) >= (int)sizeof tmp) {
        snprintf(err, errlen, "%s: path too long", path);
        return -1;
    }
    int fd = mkstemp(tmp);
    if (fd < 0) {
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
        return -1;
    }
    const char *p = data;
    size_t left = len;
    while (left > 0) {
        ssize_t w = write(fd, p, left);
        if (w < 0) {
            if (errno == EINTR)
                continue;
            snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
            close(fd);
            unlink(tmp);
            return -1;
        }
        p += w;
        left -= (size_t)w;
    }
    if (fchmod(fd, 0644) != 0 || fsync(fd) != 0) {
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
        close(fd);
        unlink(tmp);
        return -1;
    }
    if (close(fd) != 0) {
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
        unlink(tmp);
        return -1;
    }
    if (rename(tmp, path) != 0) {
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
        unlink(tmp);
        return -1;
    }
    return 0;
}

static int mkdir_p(const char *dir)
{
    char buf[4096];
    if (snprintf(buf, sizeof buf, "%s", dir) >= (int)sizeof buf) {
        errno = ENAMETOOLONG;
        return -1;
    }
    for (char *p = buf + 1; *p; ++p) {
        if (*p == '/') {
            *p = '\0';
            if (mkdir(buf, 0755) != 0 && errno != EEXIST)
                return -1;
            *p = '/';
        }
    }
    if (mkdir(buf, 0755) != 0 && errno != EEXIST)
        return -1;
    return 0;
}

int outdir_prepare(const char *dir, const char *arg, char *err, size_t errlen)
{
    struct stat st;
    const char *sep = arg ? ": " : "";
    if (!arg)
        arg = "";
    if (!dir || !*dir) {
        snprintf(err, errlen, "%s%sempty folder name", arg, sep);
        return -1;
    }
    if (mkdir_p(dir) != 0) {
        snprintf(err, errlen, "%s%scannot create folder %s: %s", arg, sep, dir, strerror(errno));
        return -1;
    }
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        snprintf(err, errlen, "%s%s%s is not a folder", arg, sep, dir);
        return -1;
    }
    if (access(dir, W_OK | X_OK) != 0) {
        snprintf(err, errlen, "%s%sfolder %s is not writable: %s", arg, sep, dir, strerror(errno));
        return -1;
    }
    return 0;
}

int outdir_new_run(const char *results_root, char *out, size_t outlen, char *err, size_t errlen)
{
    if (outdir_prepare(results_root, NULL, err, errlen) != 0)
        return -1;
    time_t now = time(NULL);
    struct tm tmv;
    localtime_r(&now, &tmv);
    char stamp[64];
    strftime(stamp, sizeof stamp, "%Y-%m-%d_%H%M%S", &tmv);
    for (int k = 0; k < 100; ++k) {
        int n = k ? snprintf(out, outlen, "%s/%s-%d", results_root, stamp, k)
                  : snprintf(out, outlen, "%s/%s", results_root, stamp);
        if (n < 0 || (size_t)n >= outlen) {
            snprintf(err, errlen, "results folder path too long");
            return -1;
        }
        if (mkdir(out, 0755) == 0)
            return 0;
        if (errno != EEXIST) {
            snprintf(err, errlen, "cannot create run folder %s: %s", out, strerror(errno));
            return -1;
        }
    }
    snprintf(err, errlen, "cannot create a new run folder under %s", results_root);
    return -1;
}

int outdir_for_command(const char *out_dir, char *run_dir, size_t run_dir_len, char *err, size_t errlen)
{
    if (!out_dir)
        return outdir_new_run("results", run_dir, run_dir_len, err, errlen);
    if (outdir_prepare(out_dir, "--out", err, errlen) != 0)
        return -1;
    snprintf(run_dir, run_dir_len, "%s", out_dir);
    return 0;
}

int outdir_set_latest(const char *results_root, const char *run_dir, char *err, size_t errlen)
{
    char link_path[4096], tmp[4096], target[4096];
    /* The link is relative, so that the results folder can be moved as a whole. */
    snprintf(target, sizeof target, "%s", run_dir);
    const char *base = strrchr(target, '/');
    base = base ? base + 1 : target;
    if (path_join(link_path, sizeof link_path, results_root, "latest") ||
        snprintf(tmp, sizeof tmp, "%s.tmp.%ld", link_path, (long)getpid()) >= (int)sizeof tmp) {
        snprintf(err, errlen, "results folder path too long");
        return -1;
    }
    unlink(tmp);
    if (symlink(base, tmp) != 0 || rename(tmp, link_path) != 0) {
        snprintf(err, errlen, "cannot point %s at %s: %s", link_path, base, strerror(errno));
        unlink(tmp);
        return -1;
    }
    return 0;
}
