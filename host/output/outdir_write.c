/* outdir_write.c - writing files: atomically (a temporary file, fsync, rename), confined to the
 * run folder, standard output and error as outputs, and the checks of an output path (see outdir.h). */
#define _GNU_SOURCE   /* getdents64 */
#include "outdir.h"
#include "outdir_internal.h"
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#define OWN_DIRS_MAX 64

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

/* A file inside a run folder (outdir_confine): each folder below the run folder is opened
 * without following links, and the file is written as a temporary file in its folder and
 * renamed over the name, which replaces a symlink, a FIFO or a device there by a regular file
 * instead of writing through it. So a link planted in a run folder (heatmap_fq2.png ->
 * /tmp/victim) never sends an output out of the folder. */
static int write_confined(const char *path, size_t rootlen, const void *data, size_t len, char *err,
                          size_t errlen)
{
    char root[OUTDIR_PATH_MAX], rest[OUTDIR_PATH_MAX];
    if (rootlen >= sizeof root || strlen(path + rootlen) >= sizeof rest) {
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(ENAMETOOLONG));
        return -1;
    }
    memcpy(root, path, rootlen);
    root[rootlen] = '\0';
    snprintf(rest, sizeof rest, "%s", path + rootlen + 1);
    int dfd = open(rootlen ? root : "/", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd < 0) {
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
        return -1;
    }
    /* the folders between the run folder and the file: real folders, no links */
    char *name = rest, *slash;
    while ((slash = strchr(name, '/')) != NULL) {
        *slash = '\0';
        if (name[0] && strcmp(name, ".") != 0) {
            if (strcmp(name, "..") == 0) {
                snprintf(err, errlen, "cannot write %s: '..' leads out of the run folder %s", path, root);
                close(dfd);
                return -1;
            }
            int sub = openat(dfd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
            if (sub < 0) {
                int e = errno;
                snprintf(err, errlen, "cannot write %s: %s%s", path,
                         e == ELOOP ? "" : strerror(e),
                         e == ELOOP ? "a folder on the way is a symlink (a run folder's outputs stay inside it)" : "");
                close(dfd);
                return -1;
            }
            close(dfd);
            dfd = sub;
        }
        name = slash + 1;
    }
    if (!name[0] || strcmp(name, ".") == 0 || strcmp(name, "..") == 0) {
        snprintf(err, errlen, "cannot write %s: not a file name", path);
        close(dfd);
        return -1;
    }
    struct stat st;
    mode_t mode = 0644;
    if (fstatat(dfd, name, &st, AT_SYMLINK_NOFOLLOW) == 0) {
        if (S_ISDIR(st.st_mode)) {
            snprintf(err, errlen, "cannot write %s: it is a folder", path);
            close(dfd);
            return -1;
        }
        if (S_ISREG(st.st_mode))
            mode = st.st_mode & 07777;
    }
    /* the temporary file's full path, for outdir_remove_own */
    size_t dirlen = strlen(path) - strlen(name);
    char tmp_name[300], tmp_full[OUTDIR_PATH_MAX];
    int fd = -1;
    for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts);
        if (snprintf(tmp_name, sizeof tmp_name, "%.200s.tmp.%ld%06lx", name, (long)getpid(),
                     ((unsigned long)ts.tv_nsec ^ ((unsigned long)attempt * 2654435761u)) & 0xffffff) >=
                (int)sizeof tmp_name ||
            dirlen + strlen(tmp_name) >= sizeof tmp_full) {
            snprintf(err, errlen, "%s: path too long", path);
            close(dfd);
            return -1;
        }
        memcpy(tmp_full, path, dirlen);
        memcpy(tmp_full + dirlen, tmp_name, strlen(tmp_name) + 1);
        memcpy(outdir_own_tmp, tmp_full, strlen(tmp_full) + 1);
        outdir_own_tmp_set = 1;
        fd = openat(dfd, tmp_name, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
        if (fd < 0 && errno != EEXIST) {
            outdir_own_tmp_set = 0;
            snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
            close(dfd);
            return -1;
        }
    }
    if (fd < 0) {
        outdir_own_tmp_set = 0;
        snprintf(err, errlen, "cannot write %s: no free temporary name", path);
        close(dfd);
        return -1;
    }
    int rc = -1;
    if (write_all(fd, data, len) != 0 || fchmod(fd, mode) != 0 || fsync(fd) != 0) {
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
        close(fd);
    } else if (close(fd) != 0 || renameat(dfd, tmp_name, dfd, name) != 0) {
        snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
    } else {
        rc = 0;
    }
    if (rc != 0)
        unlinkat(dfd, tmp_name, 0);
    outdir_own_tmp_set = 0;
    close(dfd);
    return rc;
}

int write_file_atomic(const char *path, const void *data, size_t len, char *err, size_t errlen)
{
    struct out_target t;
    if (!path || !*path) {
        snprintf(err, errlen, "cannot write '': empty file name");
        return -1;
    }
    size_t root = outdir_confined_root(path);
    if (root)
        return write_confined(path, root, data, len, err, errlen);
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
    memcpy(outdir_own_tmp, tmp, strlen(tmp) + 1);
    outdir_own_tmp_set = 1;
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
    outdir_own_tmp_set = 0;
    return rc;
}

int output_file_check(const char *flag, const char *path, char *err, size_t errlen)
{
    struct out_target t;
    if (!path || !*path) {
        snprintf(err, errlen, "%s: empty file name", flag);
        return -1;
    }
    out_resolve(path, &t);
    switch (t.kind) {
    case OUT_FD:
        return 0;
    case OUT_BAD:
        snprintf(err, errlen, "%s: cannot write %s: %s", flag, path, strerror(t.err));
        return -1;
    case OUT_FOLDER:
        snprintf(err, errlen, "%s: %s is a folder (a file name is expected)", flag, path);
        return -1;
    case OUT_THROUGH:
        if (access(t.path, W_OK) != 0) {
            snprintf(err, errlen, "%s: cannot write %s: %s", flag, path, strerror(errno));
            return -1;
        }
        return 0;
    case OUT_REGULAR:
    case OUT_NEW:
        break;
    }
    /* a file made by rename in its folder: the folder must exist and take new files */
    char dir[OUTDIR_PATH_MAX];
    snprintf(dir, sizeof dir, "%s", t.path);
    char *slash = strrchr(dir, '/');
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else if (slash == dir)
        dir[1] = '\0';
    else
        *slash = '\0';
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        snprintf(err, errlen, "%s: folder %s does not exist", flag, dir);
        return -1;
    }
    if (access(dir, W_OK | X_OK) != 0) {
        snprintf(err, errlen, "%s: folder %s is not writable: %s", flag, dir, strerror(errno));
        return -1;
    }
    return 0;
}
