/* outdir.c - atomic writes, output folders and run folders. */
#define _GNU_SOURCE   /* getdents64 */
#include "outdir.h"

#include <dirent.h>
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

/* What this process made: folders (in creation order) and the temporary file of the write in
 * progress. Fixed storage, so outdir_remove_own needs no allocation. */
#define OWN_DIRS_MAX 64
static char own_dirs[OWN_DIRS_MAX][OUTDIR_PATH_MAX];
static volatile int own_dir_count;
static char own_tmp[OUTDIR_PATH_MAX];
static volatile int own_tmp_set;

static void own_dir_add(const char *dir)
{
    if (own_dir_count >= OWN_DIRS_MAX || strlen(dir) >= OUTDIR_PATH_MAX)
        return;
    memcpy(own_dirs[own_dir_count], dir, strlen(dir) + 1);
    own_dir_count = own_dir_count + 1;
}

/* Removes everything inside the folder open as fd (depth-first), with system calls only. */
static void remove_contents_at(int fd, int depth)
{
    char buf[8192];
    if (depth > 16)
        return;
    for (int pass = 0; pass < 64; ++pass) {
        int removed = 0, more = 0;
        ssize_t n;
        while ((n = getdents64(fd, buf, sizeof buf)) > 0) {
        for (ssize_t off = 0; off < n;) {
            struct dirent64 *d = (struct dirent64 *)(buf + off);
            off += d->d_reclen;
            if (strcmp(d->d_name, ".") == 0 || strcmp(d->d_name, "..") == 0)
                continue;
            more = 1;
            if (unlinkat(fd, d->d_name, 0) == 0) {
                removed = 1;
                continue;
            }
            int sub = openat(fd, d->d_name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
            if (sub >= 0) {
                remove_contents_at(sub, depth + 1);
                close(sub);
                removed |= unlinkat(fd, d->d_name, AT_REMOVEDIR) == 0;
            }
        }
        }
        /* Entries removed while listing may hide others: list again until a pass is empty or
         * removes nothing. */
        if (!more || !removed)
            return;
        lseek(fd, 0, SEEK_SET);
    }
}

void outdir_remove_own(void)
{
    if (own_tmp_set)
        unlink(own_tmp);
    for (int i = own_dir_count - 1; i >= 0; --i) {
        int fd = open(own_dirs[i], O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (fd < 0)
            continue;
        remove_contents_at(fd, 0);
        close(fd);
        rmdir(own_dirs[i]);
    }
}

void outdir_remove_own_empty(void)
{
    for (int i = own_dir_count - 1; i >= 0; --i)
        rmdir(own_dirs[i]);   /* fails, as it should, on a folder that holds something */
}

/* The descriptor a path names when it is standard output or error or another open descriptor
 * of this process ("-", /dev/stdout, /dev/stderr, /dev/fd/N, /proc/self/fd/N), else -1. */
static int path_descriptor(const char *p)
{
    const char *num = NULL;
    if (strcmp(p, "-") == 0 || strcmp(p, "/dev/stdout") == 0)
        return 1;
    if (strcmp(p, "/dev/stderr") == 0)
        return 2;
    if (strncmp(p, "/dev/fd/", 8) == 0)
        num = p + 8;
    else if (strncmp(p, "/proc/self/fd/", 14) == 0)
        num = p + 14;
    if (!num || !*num || strspn(num, "0123456789") != strlen(num) || strlen(num) > 6)
        return -1;
    return atoi(num);
}

/* Where an output path leads. */
enum out_kind { OUT_FD, OUT_THROUGH, OUT_REGULAR, OUT_NEW, OUT_FOLDER, OUT_BAD };
struct out_target {
    enum out_kind kind;
    int fd;                         /* OUT_FD */
    char path[OUTDIR_PATH_MAX];     /* the final path, links followed */
    struct stat st;                 /* OUT_THROUGH, OUT_REGULAR */
    int err;                        /* OUT_BAD: errno */
};

/* Follows symlinks (at most 40) to the final target. */
static void out_resolve(const char *path, struct out_target *t)
{
    char cur[OUTDIR_PATH_MAX], link[OUTDIR_PATH_MAX];
    memset(t, 0, sizeof *t);
    if (snprintf(cur, sizeof cur, "%s", path) >= (int)sizeof cur) {
        t->kind = OUT_BAD;
        t->err = ENAMETOOLONG;
        return;
    }
    for (int hop = 0; hop < 40; ++hop) {
        int fd = path_descriptor(cur);
        if (fd >= 0) {
            t->kind = OUT_FD;
            t->fd = fd;
            snprintf(t->path, sizeof t->path, "%s", cur);
            return;
        }
        snprintf(t->path, sizeof t->path, "%s", cur);
        if (lstat(cur, &t->st) != 0) {
            t->kind = errno == ENOENT ? OUT_NEW : OUT_BAD;
            t->err = errno;
            return;
        }
        if (!S_ISLNK(t->st.st_mode)) {
            t->kind = S_ISREG(t->st.st_mode) ? OUT_REGULAR : S_ISDIR(t->st.st_mode) ? OUT_FOLDER : OUT_THROUGH;
            return;
        }
        ssize_t n = readlink(cur, link, sizeof link - 1);
        if (n < 0) {
            t->kind = OUT_BAD;
            t->err = errno;
            return;
        }
        link[n] = '\0';
        if (link[0] != '/' && strchr(link, ':') && stat(cur, &t->st) == 0) {
            /* A descriptor's link under /proc ("pipe:[123]"): the path itself opens it. */
            t->kind = OUT_THROUGH;
            return;
        }
        if (link[0] == '/') {
            snprintf(cur, sizeof cur, "%s", link);
        } else {
            char *slash = strrchr(cur, '/');
            size_t keep = slash ? (size_t)(slash - cur + 1) : 0;
            if (keep + (size_t)n + 1 > sizeof cur) {
                t->kind = OUT_BAD;
                t->err = ENAMETOOLONG;
                return;
            }
            memcpy(cur + keep, link, (size_t)n + 1);
        }
    }
    t->kind = OUT_BAD;
    t->err = ELOOP;
}

static int write_all(int fd, const char *p, size_t left)
{
    while (left > 0) {
        ssize_t w = write(fd, p, left);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0) {
            if (w == 0)
                errno = EIO;
            return -1;
        }
        p += w;
        left -= (size_t)w;
    }
    return 0;
}

int output_paths_same(const char *a, const char *b)
{
    struct out_target ta, tb;
    out_resolve(a, &ta);
    out_resolve(b, &tb);
    struct stat sa, sb;
    int ha = 0, hb = 0;
    if (ta.kind == OUT_FD)
        ha = fstat(ta.fd, &sa) == 0;
    else if (ta.kind != OUT_NEW && ta.kind != OUT_BAD)
        ha = stat(ta.path, &sa) == 0;
    if (tb.kind == OUT_FD)
        hb = fstat(tb.fd, &sb) == 0;
    else if (tb.kind != OUT_NEW && tb.kind != OUT_BAD)
        hb = stat(tb.path, &sb) == 0;
    if (ta.kind == OUT_FD && tb.kind == OUT_FD && ta.fd == tb.fd)
        return 1;
    if (ha && hb)
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    if (ta.kind != OUT_NEW || tb.kind != OUT_NEW)
        return 0;
    /* Two files yet to be made: the same name in the same folder. */
    char da[OUTDIR_PATH_MAX], db[OUTDIR_PATH_MAX];
    snprintf(da, sizeof da, "%s", ta.path);
    snprintf(db, sizeof db, "%s", tb.path);
    char *na = strrchr(da, '/'), *nb = strrchr(db, '/');
    const char *fa = na ? na + 1 : da, *fb = nb ? nb + 1 : db;
    if (strcmp(fa, fb) != 0)
        return 0;
    struct stat fda, fdb;
    if (na) *na = '\0';
    if (nb) *nb = '\0';
    if (stat(na ? (da[0] ? da : "/") : ".", &fda) != 0 || stat(nb ? (db[0] ? db : "/") : ".", &fdb) != 0)
        return 0;
    return fda.st_dev == fdb.st_dev && fda.st_ino == fdb.st_ino;
}

int write_file_atomic(const char *path, const void *data, size_t len, char *err, size_t errlen)
{
    struct out_target t;
    if (!path || !*path) {
        snprintf(err, errlen, "cannot write '': empty file name");
        return -1;
    }
    out_resolve(path, &t);
    switch (t.kind) {
    case OUT_BAD:
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(t.err));
        return -1;
    case OUT_FOLDER:
        snprintf(err, errlen, "cannot write %s: it is a folder", path);
        return -1;
    case OUT_FD:
        /* What stdio holds for the same descriptor goes first. */
        if (t.fd == 1)
            fflush(stdout);
        else if (t.fd == 2)
            fflush(stderr);
        if (write_all(t.fd, data, len) != 0) {
            snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
            return -1;
        }
        return 0;
    case OUT_THROUGH: {
        int fd = open(t.path, O_WRONLY | O_NOCTTY | O_CLOEXEC);
        if (fd < 0 || write_all(fd, data, len) != 0) {
            snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
            if (fd >= 0)
                close(fd);
            return -1;
        }
        if (close(fd) != 0) {
            snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
            return -1;
        }
        return 0;
    }
    case OUT_REGULAR:
    case OUT_NEW:
        break;
    }
    /* A regular file: a temporary file beside the final target, then rename over it. */
    char tmp[OUTDIR_PATH_MAX + 16];
    if (snprintf(tmp, sizeof tmp, "%s.tmp.XXXXXX", t.path) >= (int)sizeof tmp - 1) {
        snprintf(err, errlen, "%s: path too long", path);
        return -1;
    }
    mode_t mode = t.kind == OUT_REGULAR ? (t.st.st_mode & 07777) : 0644;
    int fd = mkstemp(tmp);
    if (fd < 0) {
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
        return -1;
    }
    memcpy(own_tmp, tmp, strlen(tmp) + 1);
    own_tmp_set = 1;
    int rc = -1;
    if (write_all(fd, data, len) != 0 || fchmod(fd, mode) != 0 || fsync(fd) != 0) {
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
        close(fd);
    } else if (close(fd) != 0 || rename(tmp, t.path) != 0) {
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
    } else {
        rc = 0;
    }
    if (rc != 0)
        unlink(tmp);
    own_tmp_set = 0;
    return rc;
}

/* mkdir -p; each folder it makes is recorded as this process's own. */
static int mkdir_p(const char *dir)
{
    char buf[OUTDIR_PATH_MAX];
    if (snprintf(buf, sizeof buf, "%s", dir) >= (int)sizeof buf) {
        errno = ENAMETOOLONG;
        return -1;
    }
    for (char *p = buf + 1; *p; ++p) {
        if (*p == '/') {
            *p = '\0';
            if (mkdir(buf, 0755) == 0)
                own_dir_add(buf);
            else if (errno != EEXIST)
                return -1;
            *p = '/';
        }
    }
    if (mkdir(buf, 0755) == 0)
        own_dir_add(buf);
    else if (errno != EEXIST)
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
        if (mkdir(out, 0755) == 0) {
            own_dir_add(out);
            return 0;
        }
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
