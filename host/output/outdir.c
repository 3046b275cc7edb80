/* outdir.c - atomic writes, output folders and run folders. */
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
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <time.h>
#include <unistd.h>

int path_join(char *out, size_t outlen, const char *dir, const char *name)
{
    int n = snprintf(out, outlen, "%s/%s", dir, name);
    return (n < 0 || (size_t)n >= outlen) ? -1 : 0;
}

/* What this process made: folders (in creation order) and the temporary file of the write in
 * progress. Fixed storage, so outdir_remove_own needs no allocation. Process-wide by nature, as
 * are this file's other statics: a signal handler, the stop thread and the launch watchdog tidy
 * up from them, and none of those can be handed a run object. */
#define OWN_DIRS_MAX 64
static char own_dirs[OWN_DIRS_MAX][OUTDIR_PATH_MAX];
static volatile int own_dir_count;
char outdir_own_tmp[OUTDIR_PATH_MAX];
volatile int outdir_own_tmp_set;

/* The stop-signal thread tidies up while the main thread may still be working: a folder made
 * but not yet recorded as this process's own would outlive the run. The main thread holds this
 * lock from each mkdir to its record (and through a commit); the stop thread takes it before it
 * tidies up and never gives it back, so the main thread makes nothing more after that. */
static pthread_mutex_t tidy_lock = PTHREAD_MUTEX_INITIALIZER;
static void own_dir_add(const char *dir);

/* A test hook: BRDFBENCH_TEST_PAUSE_AFTER_MKDIR=MS sleeps that long between making a run folder
 * and recording it, so that a test can stop the process there (tests/test_hostile.sh). */
static void test_pause_after_mkdir(void)
{
    const char *v = getenv("BRDFBENCH_TEST_PAUSE_AFTER_MKDIR");
    long ms = v ? strtol(v, NULL, 10) : 0;
    if (ms > 0 && ms <= 10000) {
        struct timespec ts = { ms / 1000, (ms % 1000) * 1000000L };
        nanosleep(&ts, NULL);
    }
}

/* mkdir, and the folder recorded as this process's own when it was made, under tidy_lock */
static int mkdir_own(const char *dir)
{
    pthread_mutex_lock(&tidy_lock);
    int rc = mkdir(dir, 0755);
    int saved = errno;
    if (rc == 0) {
        test_pause_after_mkdir();
        own_dir_add(dir);
    }
    pthread_mutex_unlock(&tidy_lock);
    errno = saved;
    return rc;
}

static void own_dir_add(const char *dir)
{
    if (own_dir_count >= OWN_DIRS_MAX || strlen(dir) >= OUTDIR_PATH_MAX)
        return;
    memcpy(own_dirs[own_dir_count], dir, strlen(dir) + 1);
    own_dir_count = own_dir_count + 1;
}

static void own_dir_forget(const char *dir)
{
    for (int i = 0; i < own_dir_count; ++i)
        if (strcmp(own_dirs[i], dir) == 0)
            own_dirs[i][0] = '\0';
}

/* Run folders: what is written below one never follows a link out of it (outdir_confine). */
#define CONFINED_MAX 16
static char confined[CONFINED_MAX][OUTDIR_PATH_MAX];
static struct stat confined_st[CONFINED_MAX];
static int confined_count;

void outdir_confine(const char *dir)
{
    char d[OUTDIR_PATH_MAX];
    if (!dir || !*dir || snprintf(d, sizeof d, "%s", dir) >= (int)sizeof d)
        return;
    size_t n = strlen(d);
    while (n > 1 && d[n - 1] == '/')
        d[--n] = '\0';
    for (int i = 0; i < confined_count; ++i)
        if (strcmp(confined[i], d) == 0)
            return;
    if (confined_count >= CONFINED_MAX)
        return;
    if (stat(d, &confined_st[confined_count]) != 0)
        memset(&confined_st[confined_count], 0, sizeof confined_st[0]);
    memcpy(confined[confined_count], d, n + 1);
    confined_count++;
}

/* The length of the run folder that path lies in (as spelled: "RUN/x.png", or a file directly
 * in a folder that is a run folder however spelled), or 0. */
size_t outdir_confined_root(const char *path)
{
    size_t best = 0;
    for (int i = 0; i < confined_count; ++i) {
        size_t n = strlen(confined[i]);
        if (strncmp(path, confined[i], n) == 0 && path[n] == '/' && n > best)
            best = n;
    }
    if (best)
        return best;
    /* the same folder spelled otherwise (./run, a link to it): the file's own folder */
    const char *slash = strrchr(path, '/');
    char dir[OUTDIR_PATH_MAX];
    struct stat st;
    if (!slash || (size_t)(slash - path) >= sizeof dir)
        return 0;
    size_t n = slash > path ? (size_t)(slash - path) : 1;
    memcpy(dir, path, n);
    dir[n] = '\0';
    if (stat(dir, &st) != 0)
        return 0;
    for (int i = 0; i < confined_count; ++i)
        if (confined_st[i].st_ino && confined_st[i].st_dev == st.st_dev && confined_st[i].st_ino == st.st_ino)
            return (size_t)(slash - path);
    return 0;
}

/* Scratch folders (outdir_own): removed with all they hold by every tidy-up, a signal's too. */
static char scratch_dirs[4][OUTDIR_PATH_MAX];
static volatile int scratch_count;

void outdir_own(const char *dir)
{
    own_dir_add(dir);
    if (scratch_count < 4 && strlen(dir) < OUTDIR_PATH_MAX) {
        memcpy(scratch_dirs[scratch_count], dir, strlen(dir) + 1);
        scratch_count = scratch_count + 1;
    }
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

/* The swap of a staged run folder (outdir_stage_commit) where the two-rename fallback is used:
 * 1 while the earlier run is moved aside and the new one not yet in its place. */
static volatile int swap_phase;
static char swap_final[OUTDIR_PATH_MAX], swap_old[OUTDIR_PATH_MAX + 128];

/* What an exit or a stop undoes first: the temporary file of the write in progress, and a swap
 * caught half way (the earlier run goes back to its place). */
static void undo_write_in_progress(void)
{
    if (outdir_own_tmp_set)
        unlink(outdir_own_tmp);
    if (swap_phase == 1) {
        rename(swap_old, swap_final);
        swap_phase = 0;
    }
}

void outdir_remove_own(void)
{
    undo_write_in_progress();
    for (int i = own_dir_count - 1; i >= 0; --i) {
        if (!own_dirs[i][0])
            continue;
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
        if (own_dirs[i][0])
            rmdir(own_dirs[i]);   /* fails, as it should, on a folder that holds something */
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
            if (mkdir_own(buf) != 0 && errno != EEXIST)
                return -1;
            *p = '/';
        }
    }
    if (mkdir_own(buf) != 0 && errno != EEXIST)
        return -1;
    return 0;
}

/* An existing dir that is a folder this process may write into; else -1 with the message
   (arg and sep in front of it). */
static int folder_usable(const char *dir, const char *arg, const char *sep, char *err, size_t errlen)
{
    struct stat st;
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

int outdir_prepare(const char *dir, const char *arg, char *err, size_t errlen)
{
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
    if (folder_usable(dir, arg, sep, err, errlen))
        return -1;
    /* the user's --out: one run writes it at a time */
    if (strcmp(arg, "--out") == 0 && outdir_lock(dir, arg, err, errlen) != 0)
        return -1;
    /* a folder of `brdfbench all` (its run.json) holds one run: another command's files there
       would be reported under all's command line, mixed with all's own */
    if (strcmp(arg, "--out") == 0) {
        char runjson[OUTDIR_PATH_MAX + 16];
        struct stat st;
        if (snprintf(runjson, sizeof runjson, "%s/run.json", dir) < (int)sizeof runjson && lstat(runjson, &st) == 0) {
            snprintf(err, errlen, "%s: %s is a run folder of `brdfbench all` (it holds run.json); another command's "
                     "results there would be reported as that run's (accepted: a new folder, or `all --out` "
                     "again)", arg, dir);
            return -1;
        }
    }
    outdir_confine(dir);
    return 0;
}

int outdir_check_existing(const char *dir, const char *arg, char *err, size_t errlen)
{
    struct stat st;
    if (!dir || stat(dir, &st) != 0)
        return 0;   /* not there yet: outdir_prepare makes it (or says why it cannot) */
    return folder_usable(dir, arg ? arg : "", arg ? ": " : "", err, errlen);
}

int outdir_check_latest(const char *results_root, char *err, size_t errlen)
{
    /* results/latest is the link this program keeps: anything else there is refused before the
       run, not found after it (a folder cannot be replaced, a file would be lost) */
    char latest[OUTDIR_PATH_MAX];
    struct stat lst;
    if (path_join(latest, sizeof latest, results_root, "latest") == 0 && lstat(latest, &lst) == 0 &&
        !S_ISLNK(lst.st_mode)) {
        snprintf(err, errlen, "%s is %s, not the symlink to the latest run that brdfbench keeps there (move it "
                 "away, or give --out)", latest, S_ISDIR(lst.st_mode) ? "a folder" : S_ISREG(lst.st_mode) ? "a file"
                 : "not a symlink");
        return -1;
    }
    return 0;
}

int outdir_new_run(const char *results_root, char *out, size_t outlen, char *err, size_t errlen)
{
    if (outdir_prepare(results_root, NULL, err, errlen) != 0)
        return -1;
    if (outdir_check_latest(results_root, err, errlen) != 0)
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
        if (mkdir_own(out) == 0) {
            outdir_confine(out);
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

/* The process holding an flock on the file of inode ino on device dev, from /proc/locks; 0 when
   it cannot be told. */
static long flock_holder(dev_t dev, ino_t ino)
{
    FILE *f = fopen("/proc/locks", "r");
    if (!f)
        return 0;
    char line[256];
    long holder = 0;
    while (!holder && fgets(line, sizeof line, f)) {
        char kind[16], mode[16], rw[16];
        long pid;
        unsigned maj, min;
        unsigned long long in;
        if (sscanf(line, "%*d: %15s %15s %15s %ld %x:%x:%llu", kind, mode, rw, &pid, &maj, &min, &in) == 7 &&
            strcmp(kind, "FLOCK") == 0 && in == (unsigned long long)ino && maj == major(dev) && min == minor(dev))
            holder = pid;
    }
    fclose(f);
    return holder;
}

/* The folders this process holds (an flock is per open descriptor: a second one of the same
   folder here would refuse this process itself). */
#define LOCKS_MAX 64
static struct { dev_t dev; ino_t ino; } locks_held[LOCKS_MAX];
static int nlocks_held;

int outdir_lock(const char *dir, const char *arg, char *err, size_t errlen)
{
    /* the descriptor stays open, and the lock held, until the process ends */
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        return 0;   /* no folder yet: nothing to hold */
    struct stat st;
    if (fstat(fd, &st) != 0) {
        close(fd);
        return 0;
    }
    for (int i = 0; i < nlocks_held; ++i)
        if (locks_held[i].dev == st.st_dev && locks_held[i].ino == st.st_ino) {
            close(fd);
            return 0;
        }
    if (flock(fd, LOCK_EX | LOCK_NB) == 0) {
        if (nlocks_held < LOCKS_MAX) {
            locks_held[nlocks_held].dev = st.st_dev;
            locks_held[nlocks_held++].ino = st.st_ino;
        }
        return 0;
    }
    long holder = flock_holder(st.st_dev, st.st_ino);
    close(fd);
    if (holder > 0)
        snprintf(err, errlen, "%s: %s is being written by another run (process %ld); wait for it to end or choose "
                 "another folder", arg ? arg : "run folder", dir, holder);
    else
        snprintf(err, errlen, "%s: %s is being written by another run; wait for it to end or choose another folder",
                 arg ? arg : "run folder", dir);
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

/* ---- staged run folders ------------------------------------------------------------------ */

static char stage_dir[OUTDIR_PATH_MAX + 64], stage_final[OUTDIR_PATH_MAX];
static int stage_inside;   /* the final folder is a mount point: staged inside it */

/* What a run of brdfbench leaves in its folder: result files, pictures, reports, the image
 * passes' folder, and the temporary files of an interrupted write. */
static int is_run_entry(const char *name, unsigned char type)
{
    static const char *ends[] = { ".json", ".csv", ".md", ".png", ".xml", ".txt", NULL };
    size_t n = strlen(name);
    if (type == DT_DIR)
        return strcmp(name, "render") == 0 || strcmp(name, "devices") == 0 || strncmp(name, "frontier_", 9) == 0 ||
               strncmp(name, ".render-", 8) == 0 ||
               strncmp(name, ".brdfbench-", 11) == 0;
    if (type != DT_REG && type != DT_LNK && type != DT_UNKNOWN)
        return 0;
    if (strstr(name, ".tmp."))
        return 1;
    for (int i = 0; ends[i]; ++i) {
        size_t e = strlen(ends[i]);
        if (n > e && strcmp(name + n - e, ends[i]) == 0)
            return 1;
    }
    return 0;
}

/* Returns 0 when dir holds only what a run writes, else 2 with the first other entry named. */
static int check_run_folder(const char *dir, const char *arg, char *err, size_t errlen)
{
    DIR *d = opendir(dir);
    if (!d) {
        snprintf(err, errlen, "%s: cannot read folder %s: %s", arg, dir, strerror(errno));
        return 3;
    }
    struct dirent *e;
    int rc = 0;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        unsigned char type = e->d_type;
        if (type == DT_UNKNOWN) {
            struct stat st;
            char p[OUTDIR_PATH_MAX + 300];
            snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
            if (lstat(p, &st) == 0)
                type = S_ISDIR(st.st_mode) ? DT_DIR : S_ISREG(st.st_mode) ? DT_REG : S_ISLNK(st.st_mode) ? DT_LNK
                                                                                                       : DT_FIFO;
        }
        if (!is_run_entry(e->d_name, type)) {
            snprintf(err, errlen,
                     "%s: %s holds '%.200s', which is no part of a brdfbench run; a complete run replaces its "
                     "folder as a whole (accepted: a new or empty folder, or an earlier run's folder)",
                     arg, dir, e->d_name);
            rc = 2;
            break;
        }
    }
    closedir(d);
    return rc;
}

static void remove_tree(const char *path);
static void remove_tree_at_path(const char *path) { remove_tree(path); }

/* Is process pid a brdfbench (the same program as this one)? A staging folder whose process
   is gone, or whose id now belongs to another program, is stale. */
static int same_program_alive(long pid)
{
    if (kill((pid_t)pid, 0) != 0 && errno != EPERM)
        return 0;
    char self[PATH_MAX], other[PATH_MAX], link[64];
    ssize_t a = readlink("/proc/self/exe", self, sizeof self - 1);
    snprintf(link, sizeof link, "/proc/%ld/exe", pid);
    ssize_t b = readlink(link, other, sizeof other - 1);
    if (a <= 0 || b <= 0)
        return 1;   /* no /proc to tell: a live process is taken as a run */
    self[a] = other[b] = '\0';
    return strcmp(self, other) == 0;
}

/* Other runs staging the same folder: the staging folders named like this run's (PREFIX then a
   process id) in dir. A stale one (its process gone: a run killed by SIGKILL) is removed, with
   a note; a live one that began before this run's (or at the same time, with a lower process
   id) holds the folder: its id goes to *holder and 1 is returned. */
static int other_stager(const char *dir, const char *prefix, const char *mine, long *holder)
{
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    struct stat ms;
    char mine_path[OUTDIR_PATH_MAX];
    int made = snprintf(mine_path, sizeof mine_path, "%s/%s", dir, mine);
    if (made < 0 || (size_t)made >= sizeof mine_path || stat(mine_path, &ms) != 0) {
        closedir(d);
        return 0;
    }
    int held = 0;
    size_t pl = strlen(prefix);
    long my_pid = (long)getpid();
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        if (strncmp(e->d_name, prefix, pl) != 0 || !e->d_name[pl] || strcmp(e->d_name, mine) == 0)
            continue;
        char *end = NULL;
        long pid = strtol(e->d_name + pl, &end, 10);
        if (!end || *end || pid <= 0)
            continue;
        char path[OUTDIR_PATH_MAX];
        if ((size_t)snprintf(path, sizeof path, "%s/%s", dir, e->d_name) >= sizeof path)
            continue;
        struct stat os;
        if (lstat(path, &os) != 0 || !S_ISDIR(os.st_mode))
            continue;
        if (!same_program_alive(pid)) {
            fprintf(stderr, "brdfbench: note: removed %s, the unfinished folder of an earlier run that was stopped "
                    "(process %ld)\n", path, pid);
            remove_tree_at_path(path);
            continue;
        }
        /* the earlier staging folder holds the run folder */
        int earlier = os.st_ctim.tv_sec < ms.st_ctim.tv_sec ||
                      (os.st_ctim.tv_sec == ms.st_ctim.tv_sec && (os.st_ctim.tv_nsec < ms.st_ctim.tv_nsec ||
                                                                  (os.st_ctim.tv_nsec == ms.st_ctim.tv_nsec &&
                                                                   pid < my_pid)));
        if (earlier) {
            *holder = pid;
            held = 1;
        }
    }
    closedir(d);
    return held;
}

int outdir_stage_begin(const char *final_dir, const char *arg, char *stage, size_t stagelen, char *err,
                       size_t errlen)
{
    char fin[OUTDIR_PATH_MAX];
    struct stat st;
    if (!arg)
        arg = "run folder";
    if (!final_dir || !*final_dir) {
        snprintf(err, errlen, "%s: empty folder name", arg);
        return 2;
    }
    if (snprintf(fin, sizeof fin, "%s", final_dir) >= (int)sizeof fin) {
        snprintf(err, errlen, "%s: path too long", arg);
        return 2;
    }
    size_t n = strlen(fin);
    while (n > 1 && fin[n - 1] == '/')
        fin[--n] = '\0';
    stage_inside = 0;
    if (stat(fin, &st) == 0) {
        if (!S_ISDIR(st.st_mode)) {
            snprintf(err, errlen, "%s: %s is not a folder", arg, final_dir);
            return 3;
        }
        /* the folder itself is swapped: where it really is (a link to it stays a link) */
        char real[PATH_MAX], cwd[PATH_MAX];
        if (!realpath(fin, real) || strlen(real) >= sizeof fin) {
            snprintf(err, errlen, "%s: %s: %s", arg, final_dir, strerror(errno));
            return 3;
        }
        if (getcwd(cwd, sizeof cwd)) {
            size_t rl = strlen(real);
            if (strcmp(real, "/") == 0 || (strncmp(cwd, real, rl) == 0 && (cwd[rl] == '/' || cwd[rl] == '\0'))) {
                snprintf(err, errlen, "%s: %s is the working folder or holds it; a complete run replaces its folder "
                         "as a whole (accepted: a new or empty folder, or an earlier run's folder)", arg, final_dir);
                return 2;
            }
        }
        int rc = check_run_folder(fin, arg, err, errlen);
        if (rc)
            return rc;
        if (access(fin, W_OK | X_OK) != 0) {
            snprintf(err, errlen, "%s: folder %s is not writable: %s", arg, final_dir, strerror(errno));
            return 3;
        }
        snprintf(fin, sizeof fin, "%s", real);
        /* a mount point cannot be renamed: the run is staged inside it */
        char parent[OUTDIR_PATH_MAX];
        snprintf(parent, sizeof parent, "%s", fin);
        char *slash = strrchr(parent, '/');
        if (slash == parent)
            slash[1] = '\0';
        else if (slash)
            *slash = '\0';
        struct stat pst;
        if (stat(parent, &pst) != 0 || pst.st_dev != st.st_dev || access(parent, W_OK | X_OK) != 0)
            stage_inside = 1;
    } else {
        /* a new folder: its parent made (recorded as this process's) and checked */
        char parent[OUTDIR_PATH_MAX];
        snprintf(parent, sizeof parent, "%s", fin);
        char *slash = strrchr(parent, '/');
        if (slash && slash != parent) {
            *slash = '\0';
            if (mkdir_p(parent) != 0) {
                snprintf(err, errlen, "%s: cannot create folder %s: %s", arg, final_dir, strerror(errno));
                return 3;
            }
        } else {
            snprintf(parent, sizeof parent, "%s", slash ? "/" : ".");
        }
        if (stat(parent, &st) != 0 || !S_ISDIR(st.st_mode)) {
            snprintf(err, errlen, "%s: cannot create folder %s: %s", arg, final_dir, strerror(ENOTDIR));
            return 3;
        }
        if (access(parent, W_OK | X_OK) != 0) {
            snprintf(err, errlen, "%s: cannot create folder %s: %s", arg, final_dir, strerror(errno));
            return 3;
        }
    }
    /* the staging folder: beside the final one (the same file system, so a rename moves it), or
       inside it for a mount point */
    const char *base = strrchr(fin, '/');
    int made = -1;
    if (stage_inside) {
        made = snprintf(stage_dir, sizeof stage_dir, "%s/.brdfbench-partial-%ld", fin, (long)getpid());
    } else if (base) {
        made = snprintf(stage_dir, sizeof stage_dir, "%.*s.%s.partial-%ld", (int)(base - fin + 1), fin, base + 1,
                        (long)getpid());
    } else {
        made = snprintf(stage_dir, sizeof stage_dir, ".%s.partial-%ld", fin, (long)getpid());
    }
    if (made < 0 || (size_t)made >= sizeof stage_dir || (size_t)made >= stagelen) {
        snprintf(err, errlen, "%s: path too long", arg);
        return 2;
    }
    /* a staging folder of an earlier process of the same id is stale */
    int old = open(stage_dir, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (old >= 0) {
        remove_contents_at(old, 0);
        close(old);
        rmdir(stage_dir);
    }
    if (mkdir_own(stage_dir) != 0) {
        snprintf(err, errlen, "%s: cannot create folder %s: %s", arg, stage_dir, strerror(errno));
        return 3;
    }
    if (!stage_inside && outdir_lock(fin, arg, err, errlen) != 0) {
        remove_tree_at_path(stage_dir);
        return 2;
    }
    /* Two runs into one folder at once: the later one is refused (only one run's files could
       remain, and both would say "written"); a staging folder left by a killed run is removed. */
    {
        char sdir[OUTDIR_PATH_MAX], prefix[OUTDIR_PATH_MAX];
        const char *sl = strrchr(stage_dir, '/');
        const char *sname = sl ? sl + 1 : stage_dir;
        if (sl == stage_dir)
            snprintf(sdir, sizeof sdir, "/");
        else if (sl)
            snprintf(sdir, sizeof sdir, "%.*s", (int)(sl - stage_dir), stage_dir);
        else
            snprintf(sdir, sizeof sdir, ".");
        const char *dash = strrchr(sname, '-');
        snprintf(prefix, sizeof prefix, "%.*s", dash ? (int)(dash - sname + 1) : 0, sname);
        long holder = 0;
        if (dash && other_stager(sdir, prefix, sname, &holder)) {
            remove_tree_at_path(stage_dir);
            snprintf(err, errlen, "%s: %s is being written by another run (process %ld); wait for it to end or "
                     "choose another folder", arg, final_dir, holder);
            return 2;
        }
    }
    outdir_confine(stage_dir);
    snprintf(stage_final, sizeof stage_final, "%s", fin);
    snprintf(stage, stagelen, "%s", stage_dir);
    return 0;
}

/* Removes the folder at path with all it holds (system calls only). */
static void remove_tree(const char *path)
{
    int fd = open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0)
        return;
    remove_contents_at(fd, 0);
    close(fd);
    rmdir(path);
}

/* A mount point's contents swapped entry by entry: the earlier run's entries into a folder of
 * old ones, the staged ones up into the final folder, then the old ones removed. */
static int commit_inside(char *err, size_t errlen)
{
    char old_dir[OUTDIR_PATH_MAX + 64];
    snprintf(old_dir, sizeof old_dir, "%s/.brdfbench-old-%ld", stage_final, (long)getpid());
    remove_tree(old_dir);
    if (mkdir(old_dir, 0755) != 0) {
        snprintf(err, errlen, "cannot create folder %s: %s", old_dir, strerror(errno));
        return -1;
    }
    const char *stage_base = strrchr(stage_dir, '/') + 1, *old_base = strrchr(old_dir, '/') + 1;
    DIR *d = opendir(stage_final);
    if (!d) {
        snprintf(err, errlen, "cannot read folder %s: %s", stage_final, strerror(errno));
        return -1;
    }
    int dfd = dirfd(d), sfd = open(stage_dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC),
        ofd = open(old_dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    struct dirent *e;
    int rc = 0;
    while (rc == 0 && sfd >= 0 && ofd >= 0 && (e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0 || strcmp(e->d_name, stage_base) == 0 ||
            strcmp(e->d_name, old_base) == 0)
            continue;
        if (renameat(dfd, e->d_name, ofd, e->d_name) != 0) {
            snprintf(err, errlen, "cannot move %s/%s aside: %s", stage_final, e->d_name, strerror(errno));
            rc = -1;
        }
    }
    closedir(d);
    d = rc == 0 ? opendir(stage_dir) : NULL;
    int ffd = open(stage_final, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    while (rc == 0 && d && ffd >= 0 && (e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        if (renameat(sfd, e->d_name, ffd, e->d_name) != 0) {
            snprintf(err, errlen, "cannot move %s into %s: %s", e->d_name, stage_final, strerror(errno));
            rc = -1;
        }
    }
    if (d)
        closedir(d);
    if (ffd >= 0)
        close(ffd);
    if (sfd >= 0)
        close(sfd);
    if (ofd >= 0)
        close(ofd);
    if (rc == 0) {
        remove_tree(old_dir);
        rmdir(stage_dir);
    }
    return rc;
}

static int stage_commit_locked(char *err, size_t errlen);

/* The swap and the forgetting of the folders it completes under tidy_lock: a stop signal's
 * tidy-up comes before it or after it, never in between. */
int outdir_stage_commit(char *err, size_t errlen)
{
    pthread_mutex_lock(&tidy_lock);
    int rc = stage_commit_locked(err, errlen);
    pthread_mutex_unlock(&tidy_lock);
    return rc;
}

static int stage_commit_locked(char *err, size_t errlen)
{
    if (!stage_dir[0]) {
        snprintf(err, errlen, "no staged run folder");
        return -1;
    }
    int rc = 0;
    struct stat st;
    if (stage_inside) {
        rc = commit_inside(err, errlen);
    } else if (lstat(stage_final, &st) != 0) {
        if (rename(stage_dir, stage_final) != 0) {
            snprintf(err, errlen, "cannot move %s to %s: %s", stage_dir, stage_final, strerror(errno));
            rc = -1;
        }
    } else if (renameat2(AT_FDCWD, stage_dir, AT_FDCWD, stage_final, RENAME_EXCHANGE) == 0) {
        /* one step: the new run in place, the earlier one at the staging name, removed */
        remove_tree(stage_dir);
    } else {
        /* no atomic exchange here: the earlier run aside, the new one in, the earlier removed;
           outdir_remove_own puts the earlier run back if the process is stopped in between */
        snprintf(swap_final, sizeof swap_final, "%s", stage_final);
        snprintf(swap_old, sizeof swap_old, "%s.old-%ld", stage_dir, (long)getpid());
        remove_tree(swap_old);
        if (rename(stage_final, swap_old) != 0) {
            snprintf(err, errlen, "cannot move %s aside: %s", stage_final, strerror(errno));
            rc = -1;
        } else {
            swap_phase = 1;
            if (rename(stage_dir, stage_final) != 0) {
                snprintf(err, errlen, "cannot move %s to %s: %s", stage_dir, stage_final, strerror(errno));
                rename(swap_old, stage_final);
                swap_phase = 0;
                rc = -1;
            } else {
                swap_phase = 2;
                remove_tree(swap_old);
                swap_phase = 0;
            }
        }
    }
    if (rc == 0) {
        /* the run is complete and in place: nothing of it, nor the folders made to hold it, is
           this process's to remove any more */
        for (int i = 0; i < own_dir_count; ++i)
            own_dirs[i][0] = '\0';
        stage_dir[0] = '\0';
    }
    return rc;
}

void outdir_stage_abandon(void)
{
    if (!stage_dir[0])
        return;
    remove_tree(stage_dir);
    own_dir_forget(stage_dir);
    stage_dir[0] = '\0';
}

/* ---- signals ------------------------------------------------------------------------------ */

void outdir_remove_unfinished(void)
{
    undo_write_in_progress();
    if (stage_dir[0])
        remove_tree(stage_dir);
    for (int i = scratch_count - 1; i >= 0; --i)
        remove_tree(scratch_dirs[i]);
    outdir_remove_own_empty();
}

/* The process's own stderr, kept at start: a program build redirects descriptor 2 into a file
   for a while (host/core/clsession.c), and a signal's line must not go there. */
static int signal_msg_fd = 2;

static void on_stop_signal_body(int sig)
{
    static const char msg_head[] = "brdfbench: stopped by signal ";
    static const char msg_tail[] = "; the run's unfinished outputs are removed (an earlier run in its folder stays)\n";
    char num[8];
    int n = 0, v = sig;
    char rev[8];
    do {
        rev[n++] = (char)('0' + v % 10);
        v /= 10;
    } while (v && n < 7);
    for (int i = 0; i < n; ++i)
        num[i] = rev[n - 1 - i];
    ssize_t w = write(signal_msg_fd, msg_head, sizeof msg_head - 1);
    w = write(signal_msg_fd, num, (size_t)n);
    w = write(signal_msg_fd, msg_tail, sizeof msg_tail - 1);
    (void)w;
    outdir_remove_unfinished();
}

static void on_stop_signal(int sig)
{
    on_stop_signal_body(sig);
    signal(sig, SIG_DFL);
    raise(sig);
    _exit(128 + sig);
}

void outdir_install_terminate_handler(void);   /* terminate.cpp */

static const int stop_sigs[] = { SIGINT, SIGTERM, SIGHUP, SIGQUIT };
static int stop_sig_ours[4];

static void install_stop(int i)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop_signal;
    sigfillset(&sa.sa_mask);
    sigaction(stop_sigs[i], &sa, NULL);
}

/* The stop signals are blocked in every thread (the OpenCL driver's threads, started later,
   inherit the mask) and taken by this one thread with sigwait: the handlers that the OpenCL
   compiler installs while it compiles (LLVM's, in front of ours, whose chain has been seen to
   end the process by the default action under load) then never see them. */
static sigset_t stop_set;

static void *stop_signal_thread(void *unused)
{
    (void)unused;
    for (;;) {
        int sig = 0;
        if (sigwait(&stop_set, &sig) != 0)
            continue;
        /* as the handler: the line, the tidy-up, then the default action of the signal; after
           any folder the main thread is making has been recorded (tidy_lock, kept) */
        pthread_mutex_lock(&tidy_lock);
        on_stop_signal_body(sig);
        sigset_t one;
        sigemptyset(&one);
        sigaddset(&one, sig);
        signal(sig, SIG_DFL);
        pthread_sigmask(SIG_UNBLOCK, &one, NULL);
        raise(sig);
        _exit(128 + sig);
    }
    return NULL;
}

void outdir_install_signal_handlers(void)
{
    outdir_install_terminate_handler();
    int fd = fcntl(2, F_DUPFD_CLOEXEC, 10);
    if (fd >= 0)
        signal_msg_fd = fd;
    sigemptyset(&stop_set);
    for (int i = 0; i < 4; ++i) {
        struct sigaction old;
        if (sigaction(stop_sigs[i], NULL, &old) == 0 && old.sa_handler == SIG_IGN)
            continue;   /* ignored by whoever started us (nohup): stays ignored */
        stop_sig_ours[i] = 1;
        install_stop(i);
        sigaddset(&stop_set, stop_sigs[i]);
    }
    /* the thread that takes them; without one the handlers above take them as before */
    pthread_attr_t attr;
    pthread_t t;
    if (pthread_attr_init(&attr) == 0) {
        pthread_attr_setdetachstate(&attr, PTHREAD_CREATE_DETACHED);
        if (pthread_sigmask(SIG_BLOCK, &stop_set, NULL) == 0 && pthread_create(&t, &attr, stop_signal_thread, NULL) != 0)
            pthread_sigmask(SIG_UNBLOCK, &stop_set, NULL);
        pthread_attr_destroy(&attr);
    }
}

void outdir_reassert_signal_handlers(void)
{
    for (int i = 0; i < 4; ++i)
        if (stop_sig_ours[i])
            install_stop(i);
}
