/* clsession.c - OpenCL platform/device selection, program building and error names. */
#define _POSIX_C_SOURCE 200809L
#include "clsession.h"
#include "exitcodes.h"
#include "infile.h"
#include "kernels_embedded.h"
#include "outdir.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

const char *cl_error_name(cl_int err)
{
    switch (err) {
#define E(x) case x: return #x;
    E(CL_SUCCESS) E(CL_DEVICE_NOT_FOUND) E(CL_DEVICE_NOT_AVAILABLE) E(CL_COMPILER_NOT_AVAILABLE)
    E(CL_MEM_OBJECT_ALLOCATION_FAILURE) E(CL_OUT_OF_RESOURCES) E(CL_OUT_OF_HOST_MEMORY)
    E(CL_PROFILING_INFO_NOT_AVAILABLE) E(CL_MEM_COPY_OVERLAP) E(CL_IMAGE_FORMAT_MISMATCH)
    E(CL_IMAGE_FORMAT_NOT_SUPPORTED) E(CL_BUILD_PROGRAM_FAILURE) E(CL_MAP_FAILURE)
    E(CL_MISALIGNED_SUB_BUFFER_OFFSET) E(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST)
    E(CL_COMPILE_PROGRAM_FAILURE) E(CL_LINKER_NOT_AVAILABLE) E(CL_LINK_PROGRAM_FAILURE)
    E(CL_DEVICE_PARTITION_FAILED) E(CL_KERNEL_ARG_INFO_NOT_AVAILABLE) E(CL_INVALID_VALUE)
    E(CL_INVALID_DEVICE_TYPE) E(CL_INVALID_PLATFORM) E(CL_INVALID_DEVICE) E(CL_INVALID_CONTEXT)
    E(CL_INVALID_QUEUE_PROPERTIES) E(CL_INVALID_COMMAND_QUEUE) E(CL_INVALID_HOST_PTR)
    E(CL_INVALID_MEM_OBJECT) E(CL_INVALID_IMAGE_FORMAT_DESCRIPTOR) E(CL_INVALID_IMAGE_SIZE)
    E(CL_INVALID_SAMPLER) E(CL_INVALID_BINARY) E(CL_INVALID_BUILD_OPTIONS) E(CL_INVALID_PROGRAM)
    E(CL_INVALID_PROGRAM_EXECUTABLE) E(CL_INVALID_KERNEL_NAME) E(CL_INVALID_KERNEL_DEFINITION)
    E(CL_INVALID_KERNEL) E(CL_INVALID_ARG_INDEX) E(CL_INVALID_ARG_VALUE) E(CL_INVALID_ARG_SIZE)
    E(CL_INVALID_KERNEL_ARGS) E(CL_INVALID_WORK_DIMENSION) E(CL_INVALID_WORK_GROUP_SIZE)
    E(CL_INVALID_WORK_ITEM_SIZE) E(CL_INVALID_GLOBAL_OFFSET) E(CL_INVALID_EVENT_WAIT_LIST)
    E(CL_INVALID_EVENT) E(CL_INVALID_OPERATION) E(CL_INVALID_GL_OBJECT) E(CL_INVALID_BUFFER_SIZE)
    E(CL_INVALID_MIP_LEVEL) E(CL_INVALID_GLOBAL_WORK_SIZE) E(CL_INVALID_PROPERTY)
    E(CL_INVALID_IMAGE_DESCRIPTOR) E(CL_INVALID_COMPILER_OPTIONS) E(CL_INVALID_LINKER_OPTIONS)
    E(CL_INVALID_DEVICE_PARTITION_COUNT)
#undef E
    case -1001: return "CL_PLATFORM_NOT_FOUND_KHR";
    default: return "unknown OpenCL error";
    }
}

void cl_report(const char *call, cl_int err, const char *file, int line)
{
    fprintf(stderr, "brdfbench: OpenCL error: %s failed with %s (%d) at %s:%d\n", call,
            cl_error_name(err), (int)err, file, line);
}

double wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double cl_event_seconds(cl_event ev)
{
    cl_ulong t0 = 0, t1 = 0;
    if (clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_START, sizeof t0, &t0, NULL) != CL_SUCCESS ||
        clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_END, sizeof t1, &t1, NULL) != CL_SUCCESS ||
        t1 < t0)
        return NAN;
    return 1e-9 * (double)(t1 - t0);
}

double cl_event_seconds_or_wall(cl_event ev, double wall, int *used_wall)
{
    double t = cl_event_seconds(ev);
    /* a driver that does not fill the events gives 0 or a nanosecond (rusticl on llvmpipe): the
       wall time stands in. A time far below the wall time is no sign: PoCL's first launches
       compile, outside the event. */
    int bad = !(t > 1e-8);
    if (used_wall)
        *used_wall = bad;
    return bad ? wall : t;
}

/* The launch watchdog: one thread, started at the first launch, sleeping until the armed
 * deadline. The main thread is blocked in the OpenCL wait while it is armed, so what the
 * watchdog does on firing (write(2), unlink, rmdir, _exit) needs no lock it could hold.
 * Process-wide by nature (one watchdog thread per process, shared by every session): the
 * statics below are not a run's state (host/core/run.h). */
static pthread_mutex_t wd_lock = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t wd_cond;
static int wd_started, wd_armed;
static volatile int build_progress_fd = 2;
static int progress_on = 1;

void clsession_set_progress(int on) { progress_on = on; }   /* where the watchdog writes: the real stderr during a build */
static struct timespec wd_deadline;
static char wd_message[768];
static double wd_timeout = CLSESSION_DEFAULT_TIMEOUT;
/* progress of a long wait (a program build): a line after 1 s, then every 10 s */
static char wd_progress[320];
static struct timespec wd_progress_next, wd_armed_at;
static enum clsession_timeout_source wd_timeout_source = TIMEOUT_DEFAULT;

void clsession_set_timeout(double seconds, enum clsession_timeout_source source)
{
    if (!(seconds > 0.0) || source < wd_timeout_source)
        return;
    wd_timeout = seconds;
    wd_timeout_source = source;
}

double clsession_timeout(void) { return wd_timeout; }

static int ts_before(const struct timespec *a, const struct timespec *b)
{
    return a->tv_sec < b->tv_sec || (a->tv_sec == b->tv_sec && a->tv_nsec < b->tv_nsec);
}

static void *watchdog_main(void *unused)
{
    (void)unused;
    pthread_mutex_lock(&wd_lock);
    for (;;) {
        while (!wd_armed)
            pthread_cond_wait(&wd_cond, &wd_lock);
        int progress = wd_progress[0] && ts_before(&wd_progress_next, &wd_deadline);
        int r = pthread_cond_timedwait(&wd_cond, &wd_lock, progress ? &wd_progress_next : &wd_deadline);
        if (r == ETIMEDOUT && wd_armed && progress) {
            struct timespec now;
            clock_gettime(CLOCK_MONOTONIC, &now);
            if (!ts_before(&now, &wd_progress_next)) {
                char line[400];
                double so_far = (double)(now.tv_sec - wd_armed_at.tv_sec) + 1e-9 * (double)(now.tv_nsec - wd_armed_at.tv_nsec);
                int n = snprintf(line, sizeof line, "brdfbench: %s: %.0f s so far (deadline %g s)\n", wd_progress, so_far,
                                 wd_timeout);
                ssize_t unused_w = write(build_progress_fd, line, n > 0 ? (size_t)n : 0);
                (void)unused_w;
                wd_progress_next.tv_sec += wd_progress_next.tv_sec - wd_armed_at.tv_sec < 2 ? 9 : 10;
            }
            continue;
        }
        if (r == ETIMEDOUT && wd_armed) {
            struct timespec now;
            clock_gettime(CLOCK_MONOTONIC, &now);
            if (now.tv_sec > wd_deadline.tv_sec ||
                (now.tv_sec == wd_deadline.tv_sec && now.tv_nsec >= wd_deadline.tv_nsec)) {
                ssize_t unused_w = write(build_progress_fd, wd_message, strlen(wd_message));
                (void)unused_w;
                outdir_remove_own();
                _exit(EXIT_RUNTIME);
            }
        }
    }
    return NULL;
}

static int watchdog_start(void)
{
    pthread_condattr_t attr;
    pthread_attr_t tattr;
    pthread_t thread;
    if (pthread_condattr_init(&attr) || pthread_condattr_setclock(&attr, CLOCK_MONOTONIC) ||
        pthread_cond_init(&wd_cond, &attr))
        return -1;
    pthread_condattr_destroy(&attr);
    if (pthread_attr_init(&tattr) || pthread_attr_setdetachstate(&tattr, PTHREAD_CREATE_DETACHED))
        return -1;
    int r = pthread_create(&thread, &tattr, watchdog_main, NULL);
    pthread_attr_destroy(&tattr);
    return r ? -1 : 0;
}

static void deadline_arm(const char *message, const char *progress);

void clsession_deadline_arm(cl_kernel kernel, const char *model)
{
    char name[128] = "?";
    if (kernel && clGetKernelInfo(kernel, CL_KERNEL_FUNCTION_NAME, sizeof name, name, NULL) != CL_SUCCESS)
        snprintf(name, sizeof name, "?");
    char message[768];
    snprintf(message, sizeof message,
             "brdfbench: kernel %s%s%.200s%s ran past its deadline of %g s (accepted: --timeout SECONDS, or "
             "\"timeout\" in a gates file, up to %g); the run is stopped and its unfinished outputs removed\n",
             name, model ? " of model '" : "", model ? model : "", model ? "'" : "", wd_timeout, CLSESSION_MAX_TIMEOUT);
    deadline_arm(message, NULL);
}

void clsession_deadline_arm_build(const char *what)
{
    char message[768], progress[320];
    snprintf(message, sizeof message,
             "brdfbench: %.300s ran past its deadline of %g s (accepted: --timeout SECONDS, or \"timeout\" in a "
             "gates file, up to %g); the run is stopped and its unfinished outputs removed\n",
             what, wd_timeout, CLSESSION_MAX_TIMEOUT);
    snprintf(progress, sizeof progress, "%.300s", what);
    deadline_arm(message, progress_on ? progress : NULL);
}

static void deadline_arm(const char *message, const char *progress)
{
    pthread_mutex_lock(&wd_lock);
    if (!wd_started) {
        if (watchdog_start() != 0) {
            /* Without the thread the run goes on unwatched; say so once. */
            fprintf(stderr, "brdfbench: warning: the launch deadline cannot be watched (no thread)\n");
            wd_started = -1;
        } else {
            wd_started = 1;
        }
    }
    if (wd_started == 1) {
        snprintf(wd_message, sizeof wd_message, "%s", message);
        snprintf(wd_progress, sizeof wd_progress, "%s", progress ? progress : "");
        clock_gettime(CLOCK_MONOTONIC, &wd_deadline);
        wd_armed_at = wd_deadline;
        wd_progress_next = wd_deadline;
        wd_progress_next.tv_sec += 1;
        double whole = floor(wd_timeout);
        wd_deadline.tv_sec += (time_t)whole;
        wd_deadline.tv_nsec += (long)((wd_timeout - whole) * 1e9);
        if (wd_deadline.tv_nsec >= 1000000000L) {
            wd_deadline.tv_sec += 1;
            wd_deadline.tv_nsec -= 1000000000L;
        }
        wd_armed = 1;
        pthread_cond_signal(&wd_cond);
    }
    pthread_mutex_unlock(&wd_lock);
}

void clsession_deadline_disarm(void)
{
    pthread_mutex_lock(&wd_lock);
    if (wd_armed) {
        wd_armed = 0;
        pthread_cond_signal(&wd_cond);
    }
    pthread_mutex_unlock(&wd_lock);
}

cl_int clsession_finish(struct cl_session *s, cl_kernel kernel, const char *model)
{
    clsession_deadline_arm(kernel, model);
    cl_int e = clFinish(s->queue);
    clsession_deadline_disarm();
    return e;
}

int clsession_launch(struct cl_session *s, cl_kernel kernel, cl_uint dims, const size_t *global, const size_t *local,
                     const char *model, cl_event *ev)
{
    int rc = 0;
    cl_event own = NULL;
    CL_CHECK_GOTO(clEnqueueNDRangeKernel(s->queue, kernel, dims, NULL, global, local, 0, NULL, &own), done);
    CL_CHECK_GOTO(clsession_finish(s, kernel, model), done);
done:
    if (ev && rc == 0)
        *ev = own;
    else if (own)
        clReleaseEvent(own);
    return rc;
}

int cl_run_points16(struct cl_session *s, cl_kernel k, cl_uint first_arg, const float *c, const float *n,
                    size_t count, float *out)
{
    int rc = 0;
    cl_int e;
    cl_mem bc = NULL, bn = NULL, bo = NULL;
    size_t padded = (count + 15) / 16 * 16;
    float *pc = calloc(padded, sizeof *pc), *pn = calloc(padded, sizeof *pn), *po = calloc(padded, sizeof *po);
    if (!pc || !pn || !po) {
        fprintf(stderr, "brdfbench: out of memory\n");
        rc = EXIT_RUNTIME;
        goto done;
    }
    memcpy(pc, c, count * sizeof *pc);
    memcpy(pn, n, count * sizeof *pn);
    for (size_t i = count; i < padded; ++i)
        pn[i] = 1.0f;
    bc = clCreateBuffer(s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, padded * sizeof(float), pc, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(points c)", done);
    bn = clCreateBuffer(s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, padded * sizeof(float), pn, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(points n)", done);
    bo = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, padded * sizeof(float), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(points out)", done);
    CL_SET_ARGS_GOTO(done, k, first_arg, CL_ARG(bc), CL_ARG(bn), CL_ARG(bo));
    size_t global = padded / 16;
    if ((rc = clsession_launch(s, k, 1, &global, NULL, NULL, NULL)) != 0)
        goto done;
    CL_CHECK_GOTO(clEnqueueReadBuffer(s->queue, bo, CL_TRUE, 0, padded * sizeof(float), po, 0, NULL, NULL), done);
    memcpy(out, po, count * sizeof *out);
done:
    if (bo) clReleaseMemObject(bo);
    if (bn) clReleaseMemObject(bn);
    if (bc) clReleaseMemObject(bc);
    free(po);
    free(pn);
    free(pc);
    return rc;
}

/* A string query of either kind, by its function (clGetPlatformInfo, clGetDeviceInfo). */
typedef cl_int (*info_fn)(void *object, cl_uint what, size_t size, void *value, size_t *size_ret);

static cl_int info_string(info_fn fn, void *object, cl_uint what, char *buf, size_t buflen)
{
    size_t need = 0;
    if (buflen == 0)
        return CL_INVALID_VALUE;
    buf[0] = '\0';
    cl_int e = fn(object, what, 0, NULL, &need);
    if (e != CL_SUCCESS)
        return e;
    if (need <= buflen) {
        e = fn(object, what, buflen, buf, NULL);
    } else {   /* longer than buf: read whole, keep the head */
        char *all = malloc(need);
        if (!all)
            return CL_OUT_OF_HOST_MEMORY;
        e = fn(object, what, need, all, NULL);
        if (e == CL_SUCCESS)
            memcpy(buf, all, buflen - 1);
        free(all);
    }
    buf[e == CL_SUCCESS ? buflen - 1 : 0] = '\0';
    return e;
}

static cl_int platform_info_fn(void *o, cl_uint what, size_t size, void *value, size_t *ret)
{
    return clGetPlatformInfo((cl_platform_id)o, what, size, value, ret);
}

static cl_int device_info_fn(void *o, cl_uint what, size_t size, void *value, size_t *ret)
{
    return clGetDeviceInfo((cl_device_id)o, what, size, value, ret);
}

cl_int cl_platform_string(cl_platform_id p, cl_platform_info what, char *buf, size_t buflen)
{
    return info_string(platform_info_fn, p, what, buf, buflen);
}

cl_int cl_device_string(cl_device_id d, cl_device_info what, char *buf, size_t buflen)
{
    return info_string(device_info_fn, d, what, buf, buflen);
}

cl_int cl_device_value(cl_device_id d, cl_device_info what, void *value, size_t size)
{
    cl_int e = clGetDeviceInfo(d, what, size, value, NULL);
    if (e != CL_SUCCESS)
        memset(value, 0, size);
    return e;
}

cl_int cl_set_args(cl_kernel k, cl_uint first, const struct cl_arg *args, cl_uint n, char *why, size_t whylen)
{
    for (cl_uint i = 0; i < n; ++i) {
        cl_int e = clSetKernelArg(k, first + i, args[i].size, args[i].value);
        if (e == CL_SUCCESS)
            continue;
        if (why && whylen) {
            /* the kernel by its function name ("?" where the driver cannot say it) */
            char name[128] = "?";
            if (!k || clGetKernelInfo(k, CL_KERNEL_FUNCTION_NAME, sizeof name, name, NULL) != CL_SUCCESS)
                snprintf(name, sizeof name, "?");
            snprintf(why, whylen, "clSetKernelArg(%s, argument %u) failed with %s (%d)", name, (unsigned)(first + i),
                     cl_error_name(e), (int)e);
        }
        return e;
    }
    return CL_SUCCESS;
}

int cl_set_args_report(cl_kernel k, cl_uint first, const struct cl_arg *args, cl_uint n, const char *file, int line)
{
    char why[256];
    if (cl_set_args(k, first, args, n, why, sizeof why) == CL_SUCCESS)
        return 0;
    fprintf(stderr, "brdfbench: OpenCL error: %s at %s:%d\n", why, file, line);
    return EXIT_RUNTIME;
}

static const char *no_device_hint =
    "install the CPU OpenCL driver: apt-get install pocl-opencl-icd (and ocl-icd-libopencl1)";

/* What in the environment is known to keep a driver that is installed from showing a device:
 * "; ..." clauses, or "" (the install hint alone is no help then). */
static void env_hints(char *why, size_t len)
{
    size_t used = 0;
    why[0] = '\0';
    const char *cache = getenv("POCL_CACHE_DIR");
    struct stat cst;
    if (cache && *cache && stat(cache, &cst) == 0 && (!S_ISDIR(cst.st_mode) || access(cache, W_OK | X_OK) != 0))
        used += (size_t)snprintf(why + used, len - used, "; POCL_CACHE_DIR=%.200s is not a writable folder", cache);
    const char *devs = getenv("POCL_DEVICES");
    if (devs && *devs && used < len)
        used += (size_t)snprintf(why + used, len - used, "; POCL_DEVICES=%.100s selects the devices", devs);
    struct rlimit rl;
    if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY && used < len)
        snprintf(why + used, len - used, "; the address space is limited to %llu MiB (ulimit -v), which may be too "
                 "little to load the driver", (unsigned long long)(rl.rlim_cur >> 20));
}

/* PoCL's kernel cache: POCL_CACHE_DIR, else $XDG_CACHE_HOME/pocl, else $HOME/.cache/pocl. Where
   it can be neither written nor made (HOME=/proc, a POCL_CACHE_DIR under a read-only folder),
   PoCL reports no device at all. 1 and the folder in dir when so. */
static int pocl_cache_unusable(char *dir, size_t len)
{
    const char *cache = getenv("POCL_CACHE_DIR"), *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    if (cache && *cache)
        snprintf(dir, len, "%s", cache);
    else if (xdg && *xdg)
        snprintf(dir, len, "%s/pocl", xdg);
    else if (home && *home)
        snprintf(dir, len, "%s/.cache/pocl", home);
    else
        return 0;
    /* the folder itself, or the nearest existing folder above it, must take new entries */
    char probe[PATH_MAX];
    snprintf(probe, sizeof probe, "%s", dir);
    for (;;) {
        struct stat st;
        if (stat(probe, &st) == 0)
            return !S_ISDIR(st.st_mode) || access(probe, W_OK | X_OK) != 0 || strncmp(probe, "/proc", 5) == 0 ||
                   strncmp(probe, "/sys", 4) == 0;
        char *slash = strrchr(probe, '/');
        if (!slash)
            return access(".", W_OK | X_OK) != 0;
        if (slash == probe) {
            probe[1] = '\0';
            if (stat(probe, &st) == 0)
                return access(probe, W_OK | X_OK) != 0;
            return 0;
        }
        *slash = '\0';
    }
}

int clsession_open(struct cl_session *s, int platform_index, int device_index, char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    /* PoCL keeps its compiled kernels in POCL_CACHE_DIR: one that cannot take them fails every
       build later with a log that does not say why */
    const char *cache = getenv("POCL_CACHE_DIR");
    struct stat cst;
    if (cache && *cache && stat(cache, &cst) == 0 && (!S_ISDIR(cst.st_mode) || access(cache, W_OK | X_OK) != 0)) {
        snprintf(err, errlen, "POCL_CACHE_DIR=%.300s is not a writable folder (PoCL keeps its compiled kernels there; "
                 "unset it or name a folder you can write)", cache);
        return EXIT_USAGE;
    }
    cl_uint nplat = 0;
    cl_int e = clGetPlatformIDs(0, NULL, &nplat);
    if (e == -1001 || (e == CL_SUCCESS && nplat == 0)) {
        char why[1024];
        env_hints(why, sizeof why);
        snprintf(err, errlen, "no OpenCL platform found%s; %s", why, no_device_hint);
        return EXIT_NO_DEVICE;
    }
    if (e != CL_SUCCESS) {
        snprintf(err, errlen, "clGetPlatformIDs failed with %s; %s", cl_error_name(e), no_device_hint);
        return EXIT_NO_DEVICE;
    }
    cl_platform_id plats[16];
    if (nplat > 16)
        nplat = 16;
    if ((e = clGetPlatformIDs(nplat, plats, NULL)) != CL_SUCCESS) {
        snprintf(err, errlen, "clGetPlatformIDs failed with %s; %s", cl_error_name(e), no_device_hint);
        return EXIT_NO_DEVICE;
    }
    if (platform_index >= (int)nplat) {
        snprintf(err, errlen, "--platform: %d is out of range (accepted: 0 to %u; see brdfbench list)",
                 platform_index, nplat - 1);
        return EXIT_USAGE;
    }
    int found = 0;
    for (cl_uint p = 0; p < nplat && !found; ++p) {
        if (platform_index >= 0 && (int)p != platform_index)
            continue;
        cl_uint ndev = 0;
        if (clGetDeviceIDs(plats[p], CL_DEVICE_TYPE_ALL, 0, NULL, &ndev) != CL_SUCCESS || ndev == 0)
            continue;
        cl_device_id devs[16];
        if (ndev > 16)
            ndev = 16;
        if (clGetDeviceIDs(plats[p], CL_DEVICE_TYPE_ALL, ndev, devs, NULL) != CL_SUCCESS)
            continue;
        if (device_index >= (int)ndev) {
            snprintf(err, errlen, "--device: %d is out of range for platform %u (accepted: 0 to %u)",
                     device_index, p, ndev - 1);
            return EXIT_USAGE;
        }
        int d = device_index >= 0 ? device_index : 0;
        s->platform = plats[p];
        s->device = devs[d];
        s->platform_index = (int)p;
        s->device_index = d;
        found = 1;
    }
    if (!found) {
        /* a platform is there but has no device: say what is known to cause that before the
           install hint, which does not help when the driver is installed */
        char why[1024], name[128], cache_dir[PATH_MAX];
        if (cl_platform_string(plats[platform_index >= 0 ? platform_index : 0], CL_PLATFORM_NAME, name, sizeof name) !=
            CL_SUCCESS)
            snprintf(name, sizeof name, "?");
        /* an unusable kernel cache is a runtime error, not "no device" (77 reads as skipped) */
        if (strstr(name, "Portable Computing Language") && pocl_cache_unusable(cache_dir, sizeof cache_dir)) {
            snprintf(err, errlen, "PoCL's kernel cache %.300s cannot be written or made (set by %s), so the driver "
                     "reports no device; set POCL_CACHE_DIR to a folder you can write", cache_dir,
                     getenv("POCL_CACHE_DIR") && *getenv("POCL_CACHE_DIR") ? "POCL_CACHE_DIR"
                     : getenv("XDG_CACHE_HOME") && *getenv("XDG_CACHE_HOME") ? "XDG_CACHE_HOME" : "HOME");
            return EXIT_RUNTIME;
        }
        env_hints(why, sizeof why);
        snprintf(err, errlen, "no OpenCL device found%s: platform '%s' reports none%s; if no driver is installed, %s",
                 platform_index >= 0 ? " on the chosen platform" : "", name, why, no_device_hint);
        return EXIT_NO_DEVICE;
    }
    /* What the run records and decides by: a driver that cannot say it is not used. */
#define SESSION_INFO(call, what)                                                                                    \
    if ((e = (call)) != CL_SUCCESS) {                                                                              \
        snprintf(err, errlen, "%s of the chosen device failed with %s", what, cl_error_name(e));                    \
        return EXIT_RUNTIME;                                                                                       \
    }
    cl_device_type dtype = 0;
    char ext[8192];
    SESSION_INFO(cl_platform_string(s->platform, CL_PLATFORM_NAME, s->platform_name, sizeof s->platform_name),
                 "clGetPlatformInfo(CL_PLATFORM_NAME)")
    SESSION_INFO(cl_platform_string(s->platform, CL_PLATFORM_VERSION, s->platform_version, sizeof s->platform_version),
                 "clGetPlatformInfo(CL_PLATFORM_VERSION)")
    SESSION_INFO(cl_device_string(s->device, CL_DEVICE_NAME, s->device_name, sizeof s->device_name),
                 "clGetDeviceInfo(CL_DEVICE_NAME)")
    SESSION_INFO(cl_device_string(s->device, CL_DEVICE_VERSION, s->device_version, sizeof s->device_version),
                 "clGetDeviceInfo(CL_DEVICE_VERSION)")
    SESSION_INFO(cl_device_string(s->device, CL_DRIVER_VERSION, s->driver_version, sizeof s->driver_version),
                 "clGetDeviceInfo(CL_DRIVER_VERSION)")
    SESSION_INFO(cl_device_value(s->device, CL_DEVICE_MAX_COMPUTE_UNITS, &s->compute_units, sizeof s->compute_units),
                 "clGetDeviceInfo(CL_DEVICE_MAX_COMPUTE_UNITS)")
    SESSION_INFO(cl_device_value(s->device, CL_DEVICE_TYPE, &dtype, sizeof dtype), "clGetDeviceInfo(CL_DEVICE_TYPE)")
    SESSION_INFO(cl_device_value(s->device, CL_DEVICE_GLOBAL_MEM_SIZE, &s->global_mem, sizeof s->global_mem),
                 "clGetDeviceInfo(CL_DEVICE_GLOBAL_MEM_SIZE)")
    SESSION_INFO(cl_device_value(s->device, CL_DEVICE_MAX_MEM_ALLOC_SIZE, &s->max_alloc, sizeof s->max_alloc),
                 "clGetDeviceInfo(CL_DEVICE_MAX_MEM_ALLOC_SIZE)")
    SESSION_INFO(cl_device_string(s->device, CL_DEVICE_EXTENSIONS, ext, sizeof ext), "clGetDeviceInfo(CL_DEVICE_EXTENSIONS)")
#undef SESSION_INFO
    s->is_cpu = (dtype & CL_DEVICE_TYPE_CPU) != 0;
    /* One program per built-in model where the driver compiles a program whole at build time
       (every driver but PoCL, which compiles each kernel at its first launch and so pays only
       for what a run launches); BRDFBENCH_SPECIALISE=0/1 overrides. */
    const char *spec = getenv("BRDFBENCH_SPECIALISE");
    s->specialise = spec && *spec ? atoi(spec) != 0 : strstr(s->platform_name, "Portable Computing Language") == NULL;
    s->has_fp64 = strstr(ext, "cl_khr_fp64") != NULL;
    s->has_fp16 = strstr(ext, "cl_khr_fp16") != NULL;

    s->ctx = clCreateContext(NULL, 1, &s->device, NULL, NULL, &e);
    if (e != CL_SUCCESS) {
        snprintf(err, errlen, "clCreateContext failed with %s", cl_error_name(e));
        return EXIT_RUNTIME;
    }
    s->queue = clCreateCommandQueue(s->ctx, s->device, CL_QUEUE_PROFILING_ENABLE, &e);
    if (e != CL_SUCCESS) {
        snprintf(err, errlen, "clCreateCommandQueue failed with %s", cl_error_name(e));
        clReleaseContext(s->ctx);
        s->ctx = NULL;
        return EXIT_RUNTIME;
    }
    return 0;
}

void clsession_close(struct cl_session *s)
{
    if (s->release_cache)
        s->release_cache(s);
    s->release_cache = NULL;
    if (s->release_sweeps)
        s->release_sweeps(s);
    s->release_sweeps = NULL;
    if (s->queue)
        clReleaseCommandQueue(s->queue);
    if (s->ctx)
        clReleaseContext(s->ctx);
    s->queue = NULL;
    s->ctx = NULL;
}

/* --kernel-dir: a setting of the process's flags, the same for every session it opens. */
static const char *kernel_dir_override = NULL;

void clsession_set_kernel_dir(const char *dir) { kernel_dir_override = dir; }

static char *kernel_source_raw(const char *name, size_t *len)
{
    if (kernel_dir_override) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", kernel_dir_override, name);
        /* a regular file of at most 16 MiB (a FIFO or device there is refused: infile.h) */
        char *buf = NULL, why[256];
        size_t n = 0;
        if (infile_read(path, 0, (size_t)16 << 20, &buf, &n, why, sizeof why) != 0)
            return NULL;
        if (len)
            *len = n;
        return buf;
    }
    for (int i = 0; i < embedded_kernel_count; ++i) {
        if (strcmp(embedded_kernels[i].name, name) == 0) {
            char *buf = malloc(embedded_kernels[i].size + 1);
            if (!buf)
                return NULL;
            memcpy(buf, embedded_kernels[i].data, embedded_kernels[i].size);
            buf[embedded_kernels[i].size] = '\0';
            if (len)
                *len = embedded_kernels[i].size;
            return buf;
        }
    }
    return NULL;
}

/* Replaces each line `#include "brdf_models.h"` of src by the header's text, with #line
 * directives so that build logs point at the right file and line. */
/* A growing text for expand_includes. */
struct src_text {
    char *p;
    size_t used, cap;
};

static int src_append(struct src_text *t, const char *s, size_t n)
{
    if (t->used + n + 1 > t->cap) {
        size_t cap = (t->used + n + 1) * 2;
        char *p = realloc(t->p, cap);
        if (!p)
            return -1;
        t->p = p;
        t->cap = cap;
    }
    memcpy(t->p + t->used, s, n);
    t->used += n;
    t->p[t->used] = '\0';
    return 0;
}

/* The kernel file's text with every line `#include "NAME"` replaced by NAME's text (another
 * kernel file, itself expanded), between #line directives so that a build log still names the
 * file and line. The OpenCL build gets one text and no include path (the files may be the
 * embedded ones); the host reference of a user model (hostjit.c) gets the same. */
static char *expand_includes(const char *name, int depth, size_t *len)
{
    char *raw = kernel_source_raw(name, NULL);
    if (!raw || depth > 4) {
        free(raw);
        return NULL;
    }
    struct src_text t = { NULL, 0, 0 };
    int line = 1, fail = src_append(&t, "", 0);
    for (const char *p = raw; *p && !fail; ++line) {
        const char *eol = strchr(p, '\n');
        size_t n = eol ? (size_t)(eol - p + 1) : strlen(p);
        char inner[128];
        if (sscanf(p, "#include \"%127[^\"\n]\"", inner) == 1) {
            char *sub = expand_includes(inner, depth + 1, NULL);
            char mark[300];
            int m = snprintf(mark, sizeof mark, "#line 1 \"%s\"\n", inner);
            fail = !sub || src_append(&t, mark, (size_t)m) || src_append(&t, sub, strlen(sub));
            m = snprintf(mark, sizeof mark, "\n#line %d \"%s\"\n", line + 1, name);
            fail = fail || src_append(&t, mark, (size_t)m);
            free(sub);
        } else {
            fail = src_append(&t, p, n);
        }
        p += n;
    }
    free(raw);
    if (fail) {
        free(t.p);
        return NULL;
    }
    if (len)
        *len = t.used;
    return t.p;
}

char *clsession_kernel_source(const char *name, size_t *len) { return expand_includes(name, 0, len); }

/* The OpenCL compiler of PoCL prints its own summary ("1 error generated.") on the process's
 * stderr while it builds; the build log holds the diagnostics themselves. So stderr is
 * caught in a temporary file during the build, and replayed after what brdfbench says. */
static int stderr_catch_begin(FILE **caught)
{
    *caught = tmpfile();
    if (!*caught)
        return -1;
    fflush(stderr);
    int saved = dup(2);
    if (saved < 0 || dup2(fileno(*caught), 2) < 0) {
        if (saved >= 0)
            close(saved);
        fclose(*caught);
        *caught = NULL;
        return -1;
    }
    return saved;
}

static void stderr_catch_end(int saved, FILE *caught)
{
    if (saved < 0)
        return;
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    if (caught) {
        char buf[4096];
        size_t n;
        rewind(caught);
        while ((n = fread(buf, 1, sizeof buf, caught)) > 0)
            fwrite(buf, 1, n, stderr);
        fclose(caught);
    }
}

/* Writes the first diagnostic of a build log as its first line, the way compilers do
 * ("file:line:col: error: text"): PoCL writes it as "error: file:line:col: text". */
static void print_first_diagnostic(const char *log)
{
    for (const char *p = log; p && *p;) {
        const char *eol = strchr(p, '\n');
        int n = (int)(eol ? (size_t)(eol - p) : strlen(p));
        if (n > 7 && strncmp(p, "error: ", 7) == 0) {
            /* The location ends at the first ":LINE:COL: " (a file name may hold colons). */
            const char *loc = p + 7, *end = p + n;
            for (const char *q = loc; q < end; ++q) {
                const char *r = q;
                if (*r++ != ':' || r >= end || *r < '0' || *r > '9')
                    continue;
                while (r < end && *r >= '0' && *r <= '9')
                    ++r;
                if (r >= end || *r++ != ':' || r >= end || *r < '0' || *r > '9')
                    continue;
                while (r < end && *r >= '0' && *r <= '9')
                    ++r;
                if (r + 1 < end && r[0] == ':' && r[1] == ' ') {
                    fprintf(stderr, "%.*s: error: %.*s\n", (int)(r - loc), loc, (int)(end - r - 2), r + 2);
                    return;
                }
            }
            fprintf(stderr, "%.*s\n", n, p);
            return;
        }
        p = eol ? eol + 1 : NULL;
    }
}

static int build_common(struct cl_session *s, const char *kernel_file, const char *extra_source,
                        const char *options, cl_program *out, int fail_code)
{
    int rc = 0;
    cl_int e;
    *out = NULL;
    char *src = clsession_kernel_source(kernel_file, NULL);
    if (!src) {
        fprintf(stderr, "brdfbench: kernel source %s (or a file it includes) not found%s%s\n", kernel_file,
                kernel_dir_override ? " in --kernel-dir " : "", kernel_dir_override ? kernel_dir_override : "");
        return EXIT_RUNTIME;
    }
    const char *parts[2] = { src, extra_source ? extra_source : "" };
    double t0 = wall_seconds();
    cl_program prog = clCreateProgramWithSource(s->ctx, 2, parts, NULL, &e);
    free(src);
    CL_CHECK_ERR_GOTO(e, "clCreateProgramWithSource", done);
    FILE *caught = NULL;
    char what[400];
    snprintf(what, sizeof what, "building kernels/%s%s%.300s%s", kernel_file, options && *options ? " (" : "",
             options && *options ? options : "", options && *options ? ")" : "");
    /* the progress lines and the deadline write on the real stderr, not the caught one */
    int saved_stderr = stderr_catch_begin(&caught);
    build_progress_fd = saved_stderr >= 0 ? saved_stderr : 2;
    clsession_deadline_arm_build(what);
    e = clBuildProgram(prog, 1, &s->device, options ? options : "", NULL, NULL);
    clsession_deadline_disarm();
    outdir_reassert_signal_handlers();   /* back in front of the handlers the OpenCL compiler installs */
    build_progress_fd = 2;
    s->last_build_seconds = wall_seconds() - t0;
    s->build_seconds_total += s->last_build_seconds;
    s->builds++;
    if (e != CL_SUCCESS) {
        size_t loglen = 0;
        char *log = NULL;   /* NULL: "(unavailable)" below */
        if (clGetProgramBuildInfo(prog, s->device, CL_PROGRAM_BUILD_LOG, 0, NULL, &loglen) == CL_SUCCESS &&
            (log = malloc(loglen + 1)) != NULL) {
            log[0] = '\0';
            if (clGetProgramBuildInfo(prog, s->device, CL_PROGRAM_BUILD_LOG, loglen, log, NULL) != CL_SUCCESS)
                loglen = 0;
            log[loglen] = '\0';
        }
        /* What the compiler said on stderr comes after the first diagnostic and the log. */
        int saved_again = saved_stderr;
        saved_stderr = -1;
        fflush(stderr);
        if (saved_again >= 0)
            dup2(saved_again, 2);
        print_first_diagnostic(log);
        fprintf(stderr, "brdfbench: building %s failed with %s\noptions: %s\nbuild log:\n%s\n", kernel_file,
                cl_error_name(e), options && *options ? options : "(none)", log ? log : "(unavailable)");
        stderr_catch_end(saved_again, caught);
        free(log);
        clReleaseProgram(prog);
        return fail_code;
    }
    stderr_catch_end(saved_stderr, caught);
    *out = prog;
done:
    return rc;
}

cl_kernel clsession_create_kernel(cl_program program, const char *name, cl_int *err)
{
    char what[200];
    snprintf(what, sizeof what, "creating kernel %.120s", name);
    clsession_deadline_arm_build(what);
    cl_kernel k = clCreateKernel(program, name, err);
    clsession_deadline_disarm();
    outdir_reassert_signal_handlers();
    return k;
}

int clsession_build_kernels(struct cl_session *s, const char *kernel_file, const char *extra_source,
                            const char *options, cl_program *program, int count, const char *const names[],
                            cl_kernel *const kernels[])
{
    for (int i = 0; i < count; ++i)
        *kernels[i] = NULL;
    int rc = clsession_build(s, kernel_file, extra_source, options, program);
    if (rc)
        return rc;
    for (int i = 0; i < count; ++i) {
        cl_int e;
        *kernels[i] = clsession_create_kernel(*program, names[i], &e);
        if (e != CL_SUCCESS) {
            char what[160];
            snprintf(what, sizeof what, "clCreateKernel(%s)", names[i]);
            cl_report(what, e, __FILE__, __LINE__);
            clsession_release_kernels(program, count, kernels);
            return EXIT_RUNTIME;
        }
    }
    return 0;
}

void clsession_release_kernels(cl_program *program, int count, cl_kernel *const kernels[])
{
    for (int i = count - 1; i >= 0; --i) {
        if (*kernels[i])
            clReleaseKernel(*kernels[i]);
        *kernels[i] = NULL;
    }
    if (*program)
        clReleaseProgram(*program);
    *program = NULL;
}

int clsession_build(struct cl_session *s, const char *kernel_file, const char *extra_source,
                    const char *options, cl_program *out)
{
    return build_common(s, kernel_file, extra_source, options, out, EXIT_RUNTIME);
}

int clsession_build_user(struct cl_session *s, const char *kernel_file, const char *extra_source,
                         const char *options, cl_program *out, int user_line_offset)
{
    (void)user_line_offset;
    return build_common(s, kernel_file, extra_source, options, out, EXIT_USAGE);
}

/* ---- device lists (--device all, --device 0,1, --device 0:0,1:0) ------------------------- */

/* The number of devices of every platform (at most 16 platforms, 16 devices each). */
static int device_counts(cl_uint *nplat, cl_uint ndev[16])
{
    cl_platform_id plats[16];
    cl_int e = clGetPlatformIDs(0, NULL, nplat);
    if (e != CL_SUCCESS || *nplat == 0)
        return -1;
    if (*nplat > 16)
        *nplat = 16;
    if (clGetPlatformIDs(*nplat, plats, NULL) != CL_SUCCESS)
        return -1;
    for (cl_uint p = 0; p < *nplat; ++p) {
        if (clGetDeviceIDs(plats[p], CL_DEVICE_TYPE_ALL, 0, NULL, &ndev[p]) != CL_SUCCESS)
            ndev[p] = 0;
        if (ndev[p] > 16)
            ndev[p] = 16;
    }
    return 0;
}

int clsession_device_list(const char *text, int platform, struct cl_device_ref *out, int max, char *err,
                          size_t errlen)
{
    cl_uint nplat = 0, ndev[16] = { 0 };
    if (device_counts(&nplat, ndev)) {
        snprintf(err, errlen, "no OpenCL platform found; %s", no_device_hint);
        return -EXIT_NO_DEVICE;
    }
    int n = 0;
    if (strcmp(text, "all") == 0) {
        for (cl_uint p = 0; p < nplat; ++p)
            for (cl_uint d = 0; d < ndev[p] && n < max; ++d)
                out[n++] = (struct cl_device_ref){ (int)p, (int)d };
        if (n == 0) {
            snprintf(err, errlen, "no OpenCL device found; %s", no_device_hint);
            return -EXIT_NO_DEVICE;
        }
        return n;
    }
    if (platform < 0) {   /* plain entries name devices of the first platform with one */
        for (cl_uint p = 0; p < nplat && platform < 0; ++p)
            if (ndev[p] > 0)
                platform = (int)p;
        if (platform < 0) {
            snprintf(err, errlen, "no OpenCL device found; %s", no_device_hint);
            return -EXIT_NO_DEVICE;
        }
    }
    char buf[256];
    if (strlen(text) >= sizeof buf || !*text) {
        snprintf(err, errlen, "--device: expected N, P:D, a comma-separated list of them, or all");
        return -EXIT_USAGE;
    }
    strcpy(buf, text);
    char *save = NULL;
    for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        char *colon = strchr(tok, ':'), *end = NULL;
        long p = platform, d;
        errno = 0;
        if (colon) {
            p = strtol(tok, &end, 10);
            if (end != colon || end == tok) {
                snprintf(err, errlen, "--device: '%.64s' is not N or P:D", tok);
                return -EXIT_USAGE;
            }
            tok = colon + 1;
        }
        d = strtol(tok, &end, 10);
        if (end == tok || *end || errno) {
            snprintf(err, errlen, "--device: '%.64s' is not N or P:D", tok);
            return -EXIT_USAGE;
        }
        if (p < 0 || p >= (long)nplat) {
            snprintf(err, errlen, "--device: platform %ld is out of range (accepted: 0 to %u; see brdfbench list)", p,
                     nplat - 1);
            return -EXIT_USAGE;
        }
        if (d < 0 || d >= (long)ndev[p]) {
            snprintf(err, errlen, "--device: device %ld is out of range for platform %ld (accepted: 0 to %d)", d, p,
                     (int)ndev[p] - 1);
            return -EXIT_USAGE;
        }
        if (n == max) {
            snprintf(err, errlen, "--device: at most %d devices in a list", max);
            return -EXIT_USAGE;
        }
        out[n++] = (struct cl_device_ref){ (int)p, (int)d };
    }
    if (n == 0) {
        snprintf(err, errlen, "--device: expected N, P:D, a comma-separated list of them, or all");
        return -EXIT_USAGE;
    }
    return n;
}

const size_t *clsession_group_size(const struct cl_session *s, size_t global, size_t *buf)
{
    if (s->is_cpu) {
        *buf = 1;
        return buf;
    }
    static const size_t sizes[] = { 256, 128, 64, 32 };
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; ++i)
        if (global % sizes[i] == 0) {
            *buf = sizes[i];
            return buf;
        }
    *buf = 0;
    return NULL;
}

long clsession_default_work_items(const struct cl_session *s, long max)
{
    long per_cu = s->is_cpu ? 32 : 512;
    long n = per_cu * (long)(s->compute_units ? s->compute_units : 1);
    return n > max ? max : n;
}
