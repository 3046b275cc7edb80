/* test_usermodel_code.c - a user model's code may hold no pointer (usermodel_check_code,
 * host/core/usermodel_code.c), and its host reference runs where a wild write cannot reach
 * brdfbench's memory (the sandbox of host/core/hostjit.c). No device.
 *
 * The check: texts a lobe is written with are accepted; every pointer construct of issue 31
 * (a dereference, an address-of, a cast to a pointer, '->', a subscript, asm, volatile,
 * sizeof, an address space, a call of a function that is not a pointer-free math built-in,
 * a directive in an expression) is refused, each at the column written by hand below.
 * The sandbox: a text compiled without the check (hostjit_compile directly) that stores
 * into this program's own variable, through its address passed as a parameter: called in
 * this process (hostjit_function) it changes the variable, which shows the text does what
 * it says; called through the sandbox (hostjit_eval) the variable keeps its value. A text
 * that dereferences address 8 ends the child with SIGSEGV and hostjit_eval returns -1 with
 * the signal named; values of a plain text equal the formula written again here, one by one
 * and in a batch. A whole phase in the sandbox (hostjit_isolated) hands back its values
 * (0.5 x 2, ...), not its store into the canary; a wild write there, and a write(2) the
 * filter does not allow, end it with SIGSEGV and SIGSYS. */
#include "check.h"
#include "clsession.h"
#include "exitcodes.h"
#include "hostjit.h"
#include "usermodel_check.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static void refused(const char *text, int is_file, const char *where, const char *what)
{
    char err[1024] = "";
    int rc = usermodel_check_code(text, strlen(text), is_file ? "m.cl" : "--model z", is_file, err, sizeof err);
    CHECK(rc == EXIT_USAGE, "not refused: %s", text);
    CHECK(strstr(err, where) == err, "%s: the message does not begin with %s: %s", text, where, err);
    CHECK(strstr(err, what) != NULL, "%s: the message does not say %s: %s", text, what, err);
}

static void accepted(const char *text, int is_file)
{
    char err[1024] = "";
    int rc = usermodel_check_code(text, strlen(text), is_file ? "m.cl" : "--model z", is_file, err, sizeof err);
    CHECK(rc == 0, "refused: %s: %s", text, err);
}

static volatile long canary;

struct phase_ctx {
    struct hostjit *j;
    double p0, p1;
};

static void phase_fn(void *ctx, void *out)
{
    struct phase_ctx *pc = ctx;
    double *o = out;
    for (int i = 0; i < 3; ++i)
        hostjit_eval(pc->j, 0.5 / (1 << i), 2.0 * (1 << i), pc->p0, pc->p1, &o[i]);
}

static void phase_write(void *ctx, void *out)
{
    (void)ctx;
    (void)out;
    ssize_t w = write(2, "x", 1);
    (void)w;
}

int main(void)
{
    /* accepted: what the docs' examples and the test suites write */
    accepted("c*c", 0);
    accepted("fmax(0.45*n*(c-1)+1,0)*fmax(0.45*n*(c-1)+1,0)", 0);
    accepted("c > 0.5 ? pow(c, n) : -1.0", 0);
    accepted("-c*-n + (c)*(n) + (int)n % 3 * c & 1", 0);
    accepted("(c > 0.5 && n > 1) ? native_powr(c, n) : half_exp(c)", 0);
    accepted("0.5*pow(c, n)*mul24(1, 1) + convert_float(n) + as_float(1) + (float)(c) * 2", 0);
    accepted("/* brdfbench-model\n * name: q\n * param: a 0 2 0.448\n */\n"
             "#define SQ(x) ((x)*(x))\n#define K 0.5\n"
             "static REAL helper(REAL t) { return SQ(t) * K; }\n"
             "REAL q(REAL c, REAL n, RSCALAR a)\n{\n    REAL base = fmax((a * n) * (c - 1.0) + 1.0, 0.0);\n"
             "    base *= 2; base = base & base;\n    return helper(base) * (REAL)(1) + RSPLAT(0.0);\n}\n", 1);
    accepted("/* brdfbench-model\n * name: w\n */\n#pragma OPENCL EXTENSION cl_khr_fp64 : enable\n"
             "#if defined(K)\n#endif\nREAL w(REAL c, REAL n) { while (1.0 + 1e-10 != 1.0) { } return c; }\n", 1);

    /* refused: the two inputs, then each construct (columns counted by hand) */
    refused("c + *(float*)8", 0, "--model z:5: ", "as a dereference");
    refused("sizeof(c)==8 ? (((long*)&c)[2]=0x414141414141, c) : c", 0, "--model z:1: ", "sizeof");
    refused("c * (float)*x", 0, "--model z:12: ", "after a type");
    refused("c + &n", 0, "--model z:5: ", "as an address-of");
    refused("c + (n)->x", 0, "--model z:8: ", "'->'");
    refused("c + n[2]", 0, "--model z:6: ", "'['");
    refused("c + asm(\"nop\")", 0, "--model z:5: ", "inline assembly");
    refused("c + memcpy(c, n, 8)", 0, "--model z:5: ", "'memcpy' is called");
    refused("c + fract(c, n)", 0, "--model z:5: ", "'fract' is called");
    refused("c + (sin)(n)", 0, "--model z:10: ", "a call of a parenthesised expression");
    refused("c + n\n#include \"x\"", 0, "--model z:1: ", "'#' is not accepted");
    refused("c && &&n", 0, "--model z:6: ", "as an address-of");
    /* in a file: line:column */
    refused("/* brdfbench-model\n * name: p\n */\nREAL p(REAL c, REAL n)\n{\n    float *q = 0;\n    return c;\n}\n", 1,
            "m.cl:6:11: ", "after a type");
    refused("/* brdfbench-model\n * name: p\n */\nREAL p(REAL c, REAL n) { volatile float x = c; return x; }\n", 1,
            "m.cl:4:26: ", "volatile");
    refused("/* brdfbench-model\n * name: p\n */\nREAL p(__global float *c, REAL n) { return n; }\n", 1,
            "m.cl:4:8: ", "address space");
    refused("/* brdfbench-model\n * name: p\n */\n#include \"/etc/passwd\"\nREAL p(REAL c, REAL n) { return n; }\n",
            1, "m.cl:4:1: ", "directive '#include'");
    refused("/* brdfbench-model\n * name: p\n */\n#define D *\nREAL p(REAL c, REAL n) { return D(float*)8; }\n", 1,
            "m.cl:4:11: ", "as a dereference");
    refused("/* brdfbench-model\n * name: p\n */\n#define T float\nREAL p(REAL c, REAL n) { T *q = 0; return n; }\n",
            1, "m.cl:5:28: ", "after a type");
    refused("/* brdfbench-model\n * name: p\n */\n#define M(a, b) a b\nREAL p(REAL c, REAL n) { M(float, x); return n; }\n",
            1, "m.cl:5:33: ", "a type name as the argument of macro 'M'");
    refused("/* brdfbench-model\n * name: p\n */\n#define A(f) f(1)\nREAL p(REAL c, REAL n) { return n; }\n", 1,
            "m.cl:4:14: ", "macro parameter 'f' is called");
    refused("/* brdfbench-model\n * name: p\n */\nREAL p(REAL c, REAL n) { struct s { float x; } v; return n; }\n",
            1, "m.cl:4:26: ", "struct");

    /* the sandbox */
    char *header = clsession_kernel_source("brdf_models.h", NULL);
    CHECK(header != NULL, "kernels/brdf_models.h not found");
    if (!header)
        return check_summary();
    char text[1024], err[512];
    CHECK((double)(uintptr_t)&canary == (double)(uint64_t)(uintptr_t)&canary, "address not exact in a double");
    /* the address comes in as p0 (exact in a double: below 2^53) */
    snprintf(text, sizeof text, "REAL brdf_user_eval(REAL c, REAL n, RSCALAR p0, RSCALAR p1)\n"
             "{\n    *(volatile long *)(unsigned long)p0 = 42;\n    return c * n;\n}\n");
    double addr = (double)(uintptr_t)&canary;
    struct hostjit *j = hostjit_compile(header, text, err, sizeof err);
    CHECK(j != NULL, "the canary text does not compile: %s", err);
    if (j) {
        double v = NAN;
        canary = 0;
        int rc = hostjit_eval(j, 0.5, 4.0, addr, 0, &v);
        CHECK(rc == 0 && v == 2.0, "sandboxed canary text: rc %d, value %g (0.5 * 4 = 2): %s", rc, v,
              hostjit_failure(j) ? hostjit_failure(j) : "");
        CHECK(canary == 0, "the sandboxed text wrote into this process: canary = %ld", canary);
        /* the same code in this process does write (the address is right) */
        v = hostjit_function(j)(0.5, 4.0, addr, 0);
        CHECK(canary == 42 && v == 2.0, "in this process the text should write 42: canary = %ld", canary);
        hostjit_free(j);
    }
    j = hostjit_compile(header, "REAL brdf_user_eval(REAL c, REAL n, RSCALAR p0, RSCALAR p1)\n"
                                "{\n    if (c > 0.5) *(volatile long *)8 = 0x4141;\n    return c;\n}\n", err, sizeof err);
    CHECK(j != NULL, "the wild text does not compile: %s", err);
    if (j) {
        double v = NAN;
        CHECK(hostjit_eval(j, 0.25, 4.0, 0, 0, &v) == 0 && v == 0.25, "wild text below 0.5: %g", v);
        CHECK(hostjit_eval(j, 0.75, 4.0, 0, 0, &v) == -1, "a wild write did not fail");
        const char *why = hostjit_failure(j);
        CHECK(why && strstr(why, "signal 11"), "the failure does not name SIGSEGV: %s", why ? why : "(none)");
        CHECK(hostjit_eval(j, 0.25, 4.0, 0, 0, &v) == -1, "a dead sandbox answered again");
        hostjit_free(j);
    }
    /* a phase in the sandbox (hostjit_isolated): its values come back, its writes do not */
    j = hostjit_compile(header, "REAL brdf_user_eval(REAL c, REAL n, RSCALAR p0, RSCALAR p1)\n"
                                "{\n    if (p1 > 0) *(volatile long *)(unsigned long)p1 = 7;\n"
                                "    if (p0 > 0) *(volatile long *)8 = 1;\n    return c * n;\n}\n", err, sizeof err);
    CHECK(j != NULL, "the phase text does not compile: %s", err);
    if (j) {
        struct phase_ctx pc = { j, 0, 0 };
        double out[3] = { 0, 0, 0 };
        char why[256] = "";
        canary = 0;
        pc.p1 = (double)(uintptr_t)&canary;
        int rc = hostjit_isolated(phase_fn, &pc, out, sizeof out, NULL, NULL, why, sizeof why);
        /* 0.5 * 2, 0.25 * 4, 0.125 * 8 */
        CHECK(rc == 0 && out[0] == 1.0 && out[1] == 1.0 && out[2] == 1.0, "phase: rc %d, %g %g %g: %s", rc, out[0],
              out[1], out[2], why);
        CHECK(canary == 0, "a phase's write reached this process: canary = %ld", canary);
        pc.p0 = 1;   /* the store to address 8 */
        rc = hostjit_isolated(phase_fn, &pc, out, sizeof out, NULL, NULL, why, sizeof why);
        CHECK(rc == -1 && strstr(why, "signal 11"), "a phase's wild write: rc %d: %s", rc, why);
        /* a system call the filter does not allow (write) ends the child by SIGSYS */
        rc = hostjit_isolated(phase_write, NULL, out, sizeof out, NULL, NULL, why, sizeof why);
        CHECK(rc == -1 && strstr(why, "signal 31"), "a phase's write(2): rc %d: %s", rc, why);
        hostjit_free(j);
    }
    /* values: the formula again, one by one and in a batch larger than one request (512) */
    j = hostjit_compile(header, "REAL brdf_user_eval(REAL c, REAL n, RSCALAR p0, RSCALAR p1)\n"
                                "{\n    return pow(c, n) * p0 + p1;\n}\n", err, sizeof err);
    CHECK(j != NULL, "the plain text does not compile: %s", err);
    if (j) {
        enum { N = 1200 };
        static double args[N * 4], vals[N];
        int bad = 0;
        for (int i = 0; i < N; ++i) {
            args[4 * i] = (i + 0.5) / N;
            args[4 * i + 1] = 1 + i % 50;
            args[4 * i + 2] = 0.5 + i % 3;
            args[4 * i + 3] = i % 7;
        }
        CHECK(hostjit_eval_many(j, args, N, vals) == 0, "a batch failed");
        for (int i = 0; i < N; ++i) {
            double want = pow(args[4 * i], args[4 * i + 1]) * args[4 * i + 2] + args[4 * i + 3];
            double one = NAN;
            hostjit_eval(j, args[4 * i], args[4 * i + 1], args[4 * i + 2], args[4 * i + 3], &one);
            bad += vals[i] != want || one != want;
        }
        CHECK(bad == 0, "%d of %d values differ from pow(c, n) * p0 + p1", bad, N);
        hostjit_free(j);
    }
    free(header);
    return check_summary();
}
