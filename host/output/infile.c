/* infile.c - opening and reading input files without blocking on FIFOs or devices (infile.h). */
#define _GNU_SOURCE
#include "infile.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

const char *infile_kind(mode_t mode)
{
    if (S_ISREG(mode)) return "a regular file";
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

int infile_open(const char *path, int flags, struct stat *st, char *why, size_t whylen)
{
    struct stat local;
    if (!st)
        st = &local;
    if (!path || !*path) {
        snprintf(why, whylen, "empty file name");
        return -1;
    }
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) {
        snprintf(why, whylen, "%s", strerror(errno));
        return -1;
    }
    if (fstat(fd, st) != 0) {
        snprintf(why, whylen, "%s", strerror(errno));
        close(fd);
        return -1;
    }
    int ok = S_ISREG(st->st_mode) || ((flags & INFILE_PIPE_OK) && S_ISFIFO(st->st_mode));
    if (!ok) {
        if (S_ISDIR(st->st_mode))
            snprintf(why, whylen, "is a folder, not a file");
        else
            snprintf(why, whylen, "is %s, not a regular file", infile_kind(st->st_mode));
        close(fd);
        return -1;
    }
    /* Reads block again: a regular file never waits, a pipe the user named is waited for. */
    int fl = fcntl(fd, F_GETFL);
    if (fl >= 0)
        fcntl(fd, F_SETFL, fl & ~O_NONBLOCK);
    return fd;
}

int infile_read(const char *path, int flags, size_t max, char **buf, size_t *len, char *why, size_t whylen)
{
    struct stat st;
    *buf = NULL;
    *len = 0;
    int fd = infile_open(path, flags, &st, why, whylen);
    if (fd < 0)
        return -1;
    if (S_ISREG(st.st_mode) && (unsigned long long)st.st_size > (unsigned long long)max) {
        snprintf(why, whylen, "is larger than %zu bytes (%lld)", max, (long long)st.st_size);
        close(fd);
        return -1;
    }
    size_t cap = S_ISREG(st.st_mode) ? (size_t)st.st_size + 1 : 65536;
    if (cap > max + 1)
        cap = max + 1;
    char *b = malloc(cap + 1);
    if (!b) {
        close(fd);
        return -2;
    }
    size_t n = 0;
    for (;;) {
        if (n == cap) {
            if (cap >= max + 1)
                break;
            size_t nc = cap * 2 > max + 1 ? max + 1 : cap * 2;
            char *nb = realloc(b, nc + 1);
            if (!nb) {
                free(b);
                close(fd);
                return -2;
            }
            b = nb;
            cap = nc;
        }
        ssize_t got = read(fd, b + n, cap - n);
        if (got < 0 && errno == EINTR)
            continue;
        if (got < 0) {
            snprintf(why, whylen, "%s", strerror(errno));
            free(b);
            close(fd);
            return -3;
        }
        if (got == 0)
            break;
        n += (size_t)got;
    }
    close(fd);
    if (n > max) {
        snprintf(why, whylen, "is larger than %zu bytes", max);
        free(b);
        return -1;
    }
    b[n] = '\0';
    *buf = b;
    *len = n;
    return 0;
}
