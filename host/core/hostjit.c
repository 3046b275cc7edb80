/* hostjit.c - a model's OpenCL C text compiled for the host in double (see hostjit.h). */
#define _GNU_SOURCE   /* exp10 */
#include "hostjit.h"

#include <errno.h>
#include <libtcc.h>
#include <linux/audit.h>
#include <linux/seccomp.h>
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <linux/filter.h>
#include <linux/futex.h>
#include <stdatomic.h>
#include <stddef.h>
#include <sys/mman.h>
#include <time.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

/* OpenCL C's scalar built-in functions for double, as C. Those of C99 come from the host's
 * libm (declared here, bound in bind_libm); the others follow the OpenCL C 1.2 specification
 * (section 6.12) for a scalar argument. native_* and half_* have no double form in OpenCL C;
 * in this reference they are their exact counterparts, so that the device-vs-double check
 * shows what the approximate functions cost on the device. */
static const char prelude[] =
    "#define BRDF_HOST_JIT 1\n"
    "#define REAL double\n"
    "#define RSCALAR double\n"
    "#define BRDF_HAVE_USER_MODEL 1\n"
    "typedef unsigned char uchar;\ntypedef unsigned short ushort;\n"
    "typedef unsigned int uint;\ntypedef unsigned long ulong;\n"
    "#define __kernel\n#define kernel\n#define __global\n#define global\n#define __private\n"
    "#define private\n#define __local\n#define local\n#define __constant const\n#define constant const\n"
    "#define NAN (0.0 / 0.0)\n#define INFINITY (1.0 / 0.0)\n#define HUGE_VAL INFINITY\n"
    "#define HUGE_VALF ((float)INFINITY)\n#define MAXFLOAT 3.402823466e+38F\n"
    "#define FLT_MAX 3.402823466e+38F\n#define FLT_MIN 1.175494351e-38F\n#define FLT_EPSILON 1.1920928955e-7F\n"
    "#define DBL_MAX 1.79769313486231570e+308\n#define DBL_MIN 2.225073858507201383e-308\n"
    "#define DBL_EPSILON 2.220446049250313e-16\n"
    "#define M_E 2.718281828459045235360\n#define M_LOG2E 1.442695040888963407360\n"
    "#define M_LOG10E 0.434294481903251827651\n#define M_LN2 0.693147180559945309417\n"
    "#define M_LN10 2.302585092994045684018\n#define M_PI 3.141592653589793238463\n"
    "#define M_PI_2 1.570796326794896619231\n#define M_PI_4 0.785398163397448309616\n"
    "#define M_1_PI 0.318309886183790671538\n#define M_2_PI 0.636619772367581343076\n"
    "#define M_2_SQRTPI 1.128379167095512573896\n#define M_SQRT2 1.414213562373095048802\n"
    "#define M_SQRT1_2 0.707106781186547524401\n"
    "#define M_E_F ((float)M_E)\n#define M_LOG2E_F ((float)M_LOG2E)\n#define M_LOG10E_F ((float)M_LOG10E)\n"
    "#define M_LN2_F ((float)M_LN2)\n#define M_LN10_F ((float)M_LN10)\n#define M_PI_F ((float)M_PI)\n"
    "#define M_PI_2_F ((float)M_PI_2)\n#define M_PI_4_F ((float)M_PI_4)\n#define M_1_PI_F ((float)M_1_PI)\n"
    "#define M_2_PI_F ((float)M_2_PI)\n#define M_2_SQRTPI_F ((float)M_2_SQRTPI)\n"
    "#define M_SQRT2_F ((float)M_SQRT2)\n#define M_SQRT1_2_F ((float)M_SQRT1_2)\n"
    /* C99, from libm */
    "double acos(double);double acosh(double);double asin(double);double asinh(double);double atan(double);\n"
    "double atanh(double);double cbrt(double);double ceil(double);double cos(double);double cosh(double);\n"
    "double erf(double);double erfc(double);double exp(double);double exp2(double);double exp10(double);\n"
    "double expm1(double);double fabs(double);double floor(double);double lgamma(double);double log(double);\n"
    "double log10(double);double log1p(double);double log2(double);double logb(double);double rint(double);\n"
    "double round(double);double sin(double);double sinh(double);double sqrt(double);double tan(double);\n"
    "double tanh(double);double tgamma(double);double trunc(double);\n"
    "double atan2(double,double);double copysign(double,double);double fdim(double,double);\n"
    "double fmax(double,double);double fmin(double,double);double fmod(double,double);\n"
    "double hypot(double,double);double nextafter(double,double);double pow(double,double);\n"
    "double remainder(double,double);double fma(double,double,double);double ldexp(double,int);\n"
    "int ilogb(double);double frexp(double,int*);double modf(double,double*);double remquo(double,double,int*);\n"
    "double lgamma_r(double,int*);\n"
    /* OpenCL C, written out */
    "static double powr(double x, double y) { return x < 0 ? NAN : pow(x, y); }\n"
    "static double pown(double x, int y) { return pow(x, (double)y); }\n"
    "static double rootn(double x, int y) {\n"
    "    if (y == 0) return NAN;\n"
    "    if (x < 0) return (y % 2) ? -pow(-x, 1.0 / y) : NAN;\n"
    "    return pow(x, 1.0 / y); }\n"
    "static double rsqrt(double x) { return 1.0 / sqrt(x); }\n"
    "static double cospi(double x) { return cos(M_PI * x); }\n"
    "static double sinpi(double x) { return sin(M_PI * x); }\n"
    "static double tanpi(double x) { return tan(M_PI * x); }\n"
    "static double acospi(double x) { return acos(x) / M_PI; }\n"
    "static double asinpi(double x) { return asin(x) / M_PI; }\n"
    "static double atanpi(double x) { return atan(x) / M_PI; }\n"
    "static double atan2pi(double y, double x) { return atan2(y, x) / M_PI; }\n"
    "static double mad(double a, double b, double c) { return a * b + c; }\n"
    "static double maxmag(double x, double y) {\n"
    "    return fabs(x) > fabs(y) ? x : fabs(y) > fabs(x) ? y : fmax(x, y); }\n"
    "static double minmag(double x, double y) {\n"
    "    return fabs(x) < fabs(y) ? x : fabs(y) < fabs(x) ? y : fmin(x, y); }\n"
    "static double fract(double x, double *ip) {\n"
    "    double f = floor(x); *ip = f; return fmin(x - f, 0x1.fffffffffffffp-1); }\n"
    "static double sincos(double x, double *c) { *c = cos(x); return sin(x); }\n"
    "static double clamp(double x, double lo, double hi) { return fmin(fmax(x, lo), hi); }\n"
    "static double degrees(double r) { return r * (180.0 / M_PI); }\n"
    "static double radians(double d) { return d * (M_PI / 180.0); }\n"
    "static double max(double x, double y) { return x < y ? y : x; }\n"
    "static double min(double x, double y) { return y < x ? y : x; }\n"
    "static double mix(double x, double y, double a) { return x + (y - x) * a; }\n"
    "static double step(double edge, double x) { return x < edge ? 0.0 : 1.0; }\n"
    "static double smoothstep(double e0, double e1, double x) {\n"
    "    double t = clamp((x - e0) / (e1 - e0), 0.0, 1.0); return t * t * (3.0 - 2.0 * t); }\n"
    "static double sign(double x) { return x > 0 ? 1.0 : x < 0 ? -1.0 : x == x ? x : 0.0; }\n"
    "static int isnan(double x) { return x != x; }\n"
    "static int isinf(double x) { return x == INFINITY || x == -INFINITY; }\n"
    "static int isfinite(double x) { return !isnan(x) && !isinf(x); }\n"
    "static int isnormal(double x) { return isfinite(x) && fabs(x) >= DBL_MIN; }\n"
    "static int signbit(double x) { return copysign(1.0, x) < 0; }\n"
    "static int isequal(double x, double y) { return x == y; }\n"
    "static int isnotequal(double x, double y) { return x != y; }\n"
    "static int isgreater(double x, double y) { return x > y; }\n"
    "static int isgreaterequal(double x, double y) { return x >= y; }\n"
    "static int isless(double x, double y) { return x < y; }\n"
    "static int islessequal(double x, double y) { return x <= y; }\n"
    "static int islessgreater(double x, double y) { return x < y || x > y; }\n"
    "static int isordered(double x, double y) { return x == x && y == y; }\n"
    "static int isunordered(double x, double y) { return x != x || y != y; }\n"
    /* scalar select takes b where c is non-zero; scalar any/all test the sign bit */
    "static double select(double a, double b, long c) { return c ? b : a; }\n"
    "static int any(long x) { return x < 0; }\n"
    "static int all(long x) { return x < 0; }\n"
    "#define BRDF_HOSTJIT_NATIVE(f) static double native_##f(double x) { return f(x); } \\\n"
    "                              static double half_##f(double x) { return f(x); }\n"
    "BRDF_HOSTJIT_NATIVE(cos) BRDF_HOSTJIT_NATIVE(sin) BRDF_HOSTJIT_NATIVE(tan) BRDF_HOSTJIT_NATIVE(exp)\n"
    "BRDF_HOSTJIT_NATIVE(exp2) BRDF_HOSTJIT_NATIVE(exp10) BRDF_HOSTJIT_NATIVE(log) BRDF_HOSTJIT_NATIVE(log2)\n"
    "BRDF_HOSTJIT_NATIVE(log10) BRDF_HOSTJIT_NATIVE(sqrt) BRDF_HOSTJIT_NATIVE(rsqrt)\n"
    "#undef BRDF_HOSTJIT_NATIVE\n"
    "static double native_recip(double x) { return 1.0 / x; }\n"
    "static double half_recip(double x) { return 1.0 / x; }\n"
    "static double native_divide(double x, double y) { return x / y; }\n"
    "static double half_divide(double x, double y) { return x / y; }\n"
    "static double native_powr(double x, double y) { return powr(x, y); }\n"
    "static double half_powr(double x, double y) { return powr(x, y); }\n";

static const char epilogue[] =
    "\n#line 1 \"brdfbench host evaluator\"\n"
    "double brdfbench_host_eval(double c, double n, double p0, double p1)\n"
    "{\n    return brdf_eval(BRDF_USER, c, n, p0, p1);\n}\n";


#if defined(__x86_64__)
#define HJ_AUDIT_ARCH AUDIT_ARCH_X86_64
#elif defined(__aarch64__)
#define HJ_AUDIT_ARCH AUDIT_ARCH_AARCH64
#else
#error "the host reference's sandbox knows the seccomp architecture of x86-64 and aarch64 only"
#endif

struct hj_shared;

struct hostjit {
    TCCState *tcc;
    hostjit_fn fn;
    hostjit_full_fn full;
    /* the sandbox (hostjit_eval): a child process and the memory it shares with brdfbench */
    pid_t child;
    struct hj_shared *shared;
    uint32_t seq;
    int dead;                  /* the child is gone: every evaluation fails */
    char why[256];
};

struct jit_errors {
    char *buf;
    size_t len;
    int seen;
};

static void on_error(void *opaque, const char *msg)
{
    struct jit_errors *e = opaque;
    /* The first message names the user's line. Only an implicitly declared function is
       warned about, as an error: a model calls the functions declared here, nothing else. */
    if (e->seen++ == 0 && e->buf && e->len)
        snprintf(e->buf, e->len, "%s", msg);
}

/* tcc's run-time helpers for conversions between double and unsigned 64-bit integers (its
 * libtcc1.a is not linked: -nostdlib keeps the model's code to what is bound here). */
static unsigned long long jit_fixunsdfdi(double d) { return (unsigned long long)d; }
static unsigned long long jit_fixunssfdi(float f) { return (unsigned long long)f; }
static double jit_floatundidf(unsigned long long u) { return (double)u; }
static float jit_floatundisf(unsigned long long u) { return (float)u; }
static void *jit_memcpy(void *d, const void *s, size_t n) { return memcpy(d, s, n); }
static void *jit_memmove(void *d, const void *s, size_t n) { return memmove(d, s, n); }
static void *jit_memset(void *d, int c, size_t n) { return memset(d, c, n); }

static void bind_libm(TCCState *s)
{
    static const struct { const char *name; const void *fn; } table[] = {
#define D1(f) { #f, (const void *)(double (*)(double))f }
#define D2(f) { #f, (const void *)(double (*)(double, double))f }
        D1(acos), D1(acosh), D1(asin), D1(asinh), D1(atan), D1(atanh), D1(cbrt), D1(ceil), D1(cos),
        D1(cosh), D1(erf), D1(erfc), D1(exp), D1(exp2), D1(exp10), D1(expm1), D1(fabs), D1(floor),
        D1(lgamma), D1(log), D1(log10), D1(log1p), D1(log2), D1(logb), D1(rint), D1(round), D1(sin),
        D1(sinh), D1(sqrt), D1(tan), D1(tanh), D1(tgamma), D1(trunc),
        D2(atan2), D2(copysign), D2(fdim), D2(fmax), D2(fmin), D2(fmod), D2(hypot), D2(nextafter),
        D2(pow), D2(remainder),
#undef D1
#undef D2
        { "fma", (const void *)(double (*)(double, double, double))fma },
        { "ldexp", (const void *)(double (*)(double, int))ldexp },
        { "ilogb", (const void *)(int (*)(double))ilogb },
        { "frexp", (const void *)(double (*)(double, int *))frexp },
        { "modf", (const void *)(double (*)(double, double *))modf },
        { "remquo", (const void *)(double (*)(double, double, int *))remquo },
        { "lgamma_r", (const void *)(double (*)(double, int *))lgamma_r },
        { "__fixunsdfdi", (const void *)jit_fixunsdfdi },
        { "__fixunssfdi", (const void *)jit_fixunssfdi },
        { "__floatundidf", (const void *)jit_floatundidf },
        { "__floatundisf", (const void *)jit_floatundisf },
        { "memcpy", (const void *)jit_memcpy },
        { "memmove", (const void *)jit_memmove },
        { "memset", (const void *)jit_memset },
    };
    for (size_t i = 0; i < sizeof table / sizeof table[0]; ++i)
        tcc_add_symbol(s, table[i].name, table[i].fn);
}

struct hostjit *hostjit_compile(const char *models_header, const char *model_text, char *err, size_t errlen)
{
    struct jit_errors errors = { err, errlen, 0 };
    if (err && errlen)
        err[0] = '\0';
    size_t len = strlen(prelude) + strlen(models_header) + strlen(model_text) + strlen(epilogue) + 64;
    char *src = malloc(len);
    struct hostjit *j = calloc(1, sizeof *j);
    TCCState *s = tcc_new();
    if (!src || !j || !s) {
        if (err && errlen)
            snprintf(err, errlen, "out of memory");
        goto fail;
    }
    snprintf(src, len, "%s#line 1 \"brdf_models.h\"\n%s\n%s%s", prelude, models_header, model_text, epilogue);
    tcc_set_error_func(s, &errors, on_error);
    tcc_set_options(s, "-nostdinc -nostdlib -Wimplicit-function-declaration -Werror");
    tcc_set_output_type(s, TCC_OUTPUT_MEMORY);
    bind_libm(s);
    if (tcc_compile_string(s, src) != 0 || tcc_relocate(s, TCC_RELOCATE_AUTO) < 0)
        goto fail;
    void *sym = tcc_get_symbol(s, "brdfbench_host_eval");
    if (!sym) {
        if (err && errlen && !errors.seen)
            snprintf(err, errlen, "the host evaluator has no entry point");
        goto fail;
    }
    /* An object pointer to a function pointer: what tcc_get_symbol returns is code. */
    memcpy(&j->fn, &sym, sizeof j->fn);
    void *full = tcc_get_symbol(s, "brdfbench_host_full");
    if (full)
        memcpy(&j->full, &full, sizeof j->full);
    j->tcc = s;
    free(src);
    return j;
fail:
    if (err && errlen && !err[0])
        snprintf(err, errlen, "the text does not compile as C");
    if (s)
        tcc_delete(s);
    free(j);
    free(src);
    return NULL;
}

hostjit_fn hostjit_function(const struct hostjit *j) { return j ? j->fn : NULL; }
hostjit_full_fn hostjit_full_function(const struct hostjit *j) { return j ? j->full : NULL; }

/* ---- the sandbox ------------------------------------------------------------------------ */

/* The child and brdfbench share one page-aligned block (struct hj_shared, mapped before the
   fork): brdfbench writes a request's arguments and bumps req; the child computes, writes the
   values and bumps done. Each side spins a few microseconds for the other, then sleeps on a
   futex, so that the refinement's one-value requests cost about a cache line's trip, not a
   system call each. brdfbench reads only done and the values from the block: whatever the
   child writes there is at worst wrong values, never a way into brdfbench's memory. */
enum { HJ_SCALAR = 1, HJ_FULL = 2, HJ_BATCH = 512, HJ_SPIN = 2000 };
struct hj_shared {
    _Atomic uint32_t req, done;        /* request counter; the last one answered */
    _Atomic uint32_t child_sleeps, parent_sleeps;
    uint32_t kind, count;
    double args[HJ_BATCH * 12];
    double vals[HJ_BATCH];
};

static long hj_futex(_Atomic uint32_t *addr, int op, uint32_t val, const struct timespec *timeout)
{
    return syscall(SYS_futex, (uint32_t *)addr, op, val, timeout, NULL, 0);
}

static inline void hj_pause(void)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

/* One step of a wait for the other side: a pause at first, then the core handed over, so
   that on a busy machine the other process, when it waits for this core, runs at once. */
static void hj_relax(int spins)
{
    if (spins < 256)
        hj_pause();
    else
        syscall(SYS_sched_yield);
}

static _Noreturn void child_exit(int code)
{
    /* _exit calls exit_group: the plain exit system call, which the filter allows too */
    for (;;)
        syscall(SYS_exit, code);
}

/* seccomp's filter: exit, exit_group, futex and sched_yield; any other system call kills the
   child. (Strict mode would allow read and write instead of futex.) */
static int enter_seccomp(int memory)
{
    /* memory (a phase's child, which runs brdfbench's own code around the model's): brk,
       munmap, mremap, madvise and mmap without PROT_EXEC too, for malloc; never mprotect,
       so no page it writes becomes code. */
    struct sock_filter f[] = {
        BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(struct seccomp_data, arch)),
        BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, HJ_AUDIT_ARCH, 1, 0),
        BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_KILL_PROCESS),
        BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(struct seccomp_data, nr)),
        BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_futex, 12, 0),
        BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_exit, 11, 0),
        BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_exit_group, 10, 0),
        BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_sched_yield, 9, 0),
        BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, memory ? SYS_brk : SYS_exit, 8, 0),
        BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, memory ? SYS_munmap : SYS_exit, 7, 0),
        BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, memory ? SYS_mremap : SYS_exit, 6, 0),
        BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, memory ? SYS_madvise : SYS_exit, 5, 0),
        BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, memory ? SYS_mmap : SYS_exit, 1, 0),
        BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_KILL_PROCESS),
        /* mmap: not with PROT_EXEC (its third argument) */
        BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(struct seccomp_data, args[2])),
        BPF_JUMP(BPF_JMP | BPF_JSET | BPF_K, PROT_EXEC, 0, 1),
        BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_KILL_PROCESS),
        BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ALLOW),
    };
    struct sock_fprog prog = { (unsigned short)(sizeof f / sizeof f[0]), f };
    if (prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0)
        return -1;
    return prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &prog);
}

/* A child's setup before it runs any of the model's code. */
static void child_harden(pid_t parent, int memory)
{
    /* Die with brdfbench; take no signal handler of brdfbench's along; leave no core file. */
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent)
        _exit(1);
    for (int sig = 1; sig < NSIG; ++sig)
        signal(sig, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, NULL);
    struct rlimit zero = { 0, 0 };
    setrlimit(RLIMIT_CORE, &zero);
    /* Every descriptor (the terminal, the run's output files, PoCL's) is closed: no system
       call could reach one anyway, this makes it so twice. */
    if (syscall(SYS_close_range, 0u, ~0u, 0u) != 0)
        for (int k = 0; k < 65536; ++k)
            close(k);
    if (enter_seccomp(memory) != 0)
        child_exit(1);
}

static _Noreturn void child_main(const struct hostjit *j, struct hj_shared *sh, pid_t parent)
{
    child_harden(parent, 0);
    uint32_t seen = 0;
    for (;;) {
        uint32_t r;
        int spins = 0;
        while ((r = atomic_load_explicit(&sh->req, memory_order_acquire)) == seen) {
            if (++spins < HJ_SPIN) {
                hj_relax(spins);
                continue;
            }
            atomic_store(&sh->child_sleeps, 1);
            if (atomic_load(&sh->req) == seen)
                hj_futex(&sh->req, FUTEX_WAIT, seen, NULL);
            atomic_store(&sh->child_sleeps, 0);
            spins = 0;
        }
        seen = r;
        uint32_t count = sh->count > HJ_BATCH ? HJ_BATCH : sh->count;
        size_t per = sh->kind == HJ_SCALAR ? 4 : 12;
        for (uint32_t i = 0; i < count; ++i) {
            const double *a = sh->args + i * per;
            sh->vals[i] = sh->kind == HJ_SCALAR ? j->fn(a[0], a[1], a[2], a[3])
                        : j->full ? j->full(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], a[9], a[10], a[11])
                                  : NAN;
        }
        atomic_store(&sh->done, r);
        if (atomic_load(&sh->parent_sleeps))
            hj_futex(&sh->done, FUTEX_WAKE, 1, NULL);
    }
}

/* How the child ended, in j->why. */
static void child_gone(struct hostjit *j)
{
    j->dead = 1;
    int status = 0;
    pid_t r;
    do
        r = waitpid(j->child, &status, 0);
    while (r < 0 && errno == EINTR);
    if (r == j->child && WIFSIGNALED(status))
        snprintf(j->why, sizeof j->why, "its process was killed by signal %d (%s)%s", WTERMSIG(status),
                 strsignal(WTERMSIG(status)),
                 WTERMSIG(status) == SIGSYS || WTERMSIG(status) == SIGKILL
                     ? ": a system call, which the sandbox does not allow, or an outside kill"
                 : WTERMSIG(status) == SIGSEGV || WTERMSIG(status) == SIGBUS
                     ? ": the model's code read or wrote memory outside its own variables"
                     : "");
    else if (r == j->child && WIFEXITED(status))
        snprintf(j->why, sizeof j->why, "its process ended (status %d) instead of answering", WEXITSTATUS(status));
    else
        snprintf(j->why, sizeof j->why, "its process stopped answering");
    j->child = 0;
}

static int start_child(struct hostjit *j)
{
    struct hj_shared *sh = mmap(NULL, sizeof *sh, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (sh == MAP_FAILED) {
        snprintf(j->why, sizeof j->why, "no memory for its sandbox: %s", strerror(errno));
        j->dead = 1;
        return -1;
    }
    pid_t parent = getpid();
    fflush(NULL);   /* no buffered output of brdfbench's is written twice */
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(j->why, sizeof j->why, "no process for its sandbox: %s", strerror(errno));
        munmap(sh, sizeof *sh);
        j->dead = 1;
        return -1;
    }
    if (pid == 0)
        child_main(j, sh, parent);
    j->child = pid;
    j->shared = sh;
    return 0;
}

/* Waits for the child's answer to request r: spins, then sleeps 50 ms at a time, looking
   between sleeps whether the child is still there. */
static int wait_answer(struct hostjit *j, uint32_t r)
{
    struct hj_shared *sh = j->shared;
    int spins = 0;
    while (atomic_load_explicit(&sh->done, memory_order_acquire) != r) {
        if (++spins < HJ_SPIN) {
            hj_relax(spins);
            continue;
        }
        spins = 0;
        atomic_store(&sh->parent_sleeps, 1);
        uint32_t d = atomic_load(&sh->done);
        if (d != r) {
            struct timespec ts = { 0, 50000000L };
            hj_futex(&sh->done, FUTEX_WAIT, d, &ts);
        }
        atomic_store(&sh->parent_sleeps, 0);
        int status;
        pid_t w = waitpid(j->child, &status, WNOHANG);
        if (w == j->child || (w < 0 && errno != EINTR)) {
            /* gone: child_gone reads its status, so put it back in the way of waitpid */
            j->dead = 1;
            if (w == j->child) {
                if (WIFSIGNALED(status))
                    snprintf(j->why, sizeof j->why, "its process was killed by signal %d (%s)%s", WTERMSIG(status),
                             strsignal(WTERMSIG(status)),
                             WTERMSIG(status) == SIGSYS || WTERMSIG(status) == SIGKILL
                                 ? ": a system call, which the sandbox does not allow, or an outside kill"
                             : WTERMSIG(status) == SIGSEGV || WTERMSIG(status) == SIGBUS
                                 ? ": the model's code read or wrote memory outside its own variables"
                                 : "");
                else
                    snprintf(j->why, sizeof j->why, "its process ended (status %d) instead of answering",
                             WIFEXITED(status) ? WEXITSTATUS(status) : -1);
                j->child = 0;
            } else {
                child_gone(j);
            }
            return -1;
        }
    }
    return 0;
}

/* Inside a phase's child (hostjit_isolated): the evaluations call the code directly, and
   mark their progress in the block shared with brdfbench, whose deadline watches it. */
struct hj_phase {
    _Atomic uint64_t progress;
    double c, n;
    unsigned char out[];
};
/* Set only in a phase's forked child: what that process is, so it is the process's, not a run's. */
static struct hj_phase *hj_inside;

/* Requests handed to a sandbox's child in this process (hostjit_round_trips): each costs a
   trip to the other process and back, a scheduler's wake-up each way on a busy machine. */
static _Atomic unsigned long hj_round_trips;

unsigned long hostjit_round_trips(void) { return atomic_load(&hj_round_trips); }

static int eval_in_child(struct hostjit *j, uint32_t kind, const double *args, size_t count, double *out)
{
    if (!j || j->dead)
        return -1;
    if (hj_inside) {
        size_t per = kind == HJ_SCALAR ? 4 : 12;
        for (size_t i = 0; i < count; ++i) {
            const double *a = args + i * per;
            hj_inside->c = kind == HJ_SCALAR ? a[0] : NAN;
            hj_inside->n = kind == HJ_SCALAR ? a[1] : a[9];
            atomic_fetch_add(&hj_inside->progress, 1);
            out[i] = kind == HJ_SCALAR ? j->fn(a[0], a[1], a[2], a[3])
                   : j->full ? j->full(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], a[9], a[10], a[11])
                             : NAN;
        }
        return 0;
    }
    if (!j->child && start_child(j) != 0)
        return -1;
    struct hj_shared *sh = j->shared;
    size_t per = kind == HJ_SCALAR ? 4 : 12;
    while (count) {
        uint32_t now = count > HJ_BATCH ? HJ_BATCH : (uint32_t)count;
        sh->kind = kind;
        sh->count = now;
        memcpy(sh->args, args, now * per * sizeof(double));
        uint32_t r = ++j->seq;
        atomic_fetch_add(&hj_round_trips, 1);
        atomic_store(&sh->req, r);
        if (atomic_load(&sh->child_sleeps))
            hj_futex(&sh->req, FUTEX_WAKE, 1, NULL);
        if (wait_answer(j, r) != 0)
            return -1;
        memcpy(out, sh->vals, now * sizeof(double));
        args += now * per;
        out += now;
        count -= now;
    }
    return 0;
}

static void describe_status(int status, char *why, size_t whylen)
{
    if (WIFSIGNALED(status))
        snprintf(why, whylen, "its process was killed by signal %d (%s)%s", WTERMSIG(status),
                 strsignal(WTERMSIG(status)),
                 WTERMSIG(status) == SIGSYS || WTERMSIG(status) == SIGKILL
                     ? ": a system call, which the sandbox does not allow, or an outside kill"
                 : WTERMSIG(status) == SIGSEGV || WTERMSIG(status) == SIGBUS
                     ? ": the model's code read or wrote memory outside its own variables"
                     : "");
    else
        snprintf(why, whylen, "its process ended with status %d", WIFEXITED(status) ? WEXITSTATUS(status) : -1);
}

int hostjit_isolated(void (*fn)(void *ctx, void *out), void *ctx, void *out, size_t outlen,
                     void (*tick)(void *tctx, double c, double n), void *tctx, char *why, size_t whylen)
{
    size_t bytes = sizeof(struct hj_phase) + outlen;
    struct hj_phase *ph = mmap(NULL, bytes, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (ph == MAP_FAILED) {
        snprintf(why, whylen, "no memory for its sandbox: %s", strerror(errno));
        return -1;
    }
    pid_t parent = getpid();
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(why, whylen, "no process for its sandbox: %s", strerror(errno));
        munmap(ph, bytes);
        return -1;
    }
    if (pid == 0) {
        child_harden(parent, 1);
        hj_inside = ph;
        fn(ctx, ph->out);
        child_exit(0);
    }
    /* Waits, looking every few milliseconds whether the child ended and whether it went on
       to another value (tick: brdfbench's deadline counts from the last one). */
    uint64_t seen = 0;
    int status = 0, rc = -1;
    long sleep_ns = 200000;
    for (;;) {
        pid_t w = waitpid(pid, &status, WNOHANG);
        if (w == pid)
            break;
        if (w < 0 && errno != EINTR) {
            snprintf(why, whylen, "its process was lost: %s", strerror(errno));
            munmap(ph, bytes);
            return -1;
        }
        uint64_t p = atomic_load(&ph->progress);
        if (p != seen && tick) {
            seen = p;
            tick(tctx, ph->c, ph->n);
        }
        struct timespec ts = { 0, sleep_ns };
        nanosleep(&ts, NULL);
        if (sleep_ns < 10000000L)
            sleep_ns *= 2;
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
        memcpy(out, ph->out, outlen);
        rc = 0;
    } else {
        describe_status(status, why, whylen);
    }
    munmap(ph, bytes);
    return rc;
}

int hostjit_eval_many(struct hostjit *j, const double *args, size_t count, double *out)
{
    return eval_in_child(j, HJ_SCALAR, args, count, out);
}

int hostjit_eval(struct hostjit *j, double c, double n, double p0, double p1, double *out)
{
    double a[4] = { c, n, p0, p1 };
    return eval_in_child(j, HJ_SCALAR, a, 1, out);
}

int hostjit_eval_full(struct hostjit *j, const double args[12], double *out)
{
    return eval_in_child(j, HJ_FULL, args, 1, out);
}

const char *hostjit_failure(const struct hostjit *j) { return j && j->dead ? j->why : NULL; }

void hostjit_free(struct hostjit *j)
{
    if (!j)
        return;
    if (j->child) {
        kill(j->child, SIGKILL);
        while (waitpid(j->child, NULL, 0) < 0 && errno == EINTR)
            ;
    }
    if (j->shared)
        munmap(j->shared, sizeof *j->shared);
    tcc_delete(j->tcc);
    free(j);
}
