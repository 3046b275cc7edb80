/* bench_hostjit.c - what the host reference's sandbox (host/core/hostjit.c) costs per value:
 * the same compiled model called in this process (hostjit_function, as before the sandbox),
 * through the sandbox one value per request (as the accuracy sweep's refinement asks) and in
 * batches of 512. Prints the median of ROUNDS rounds of each, interleaved, in ns per value,
 * and the ratios. Run by scripts/bench_hostref_sandbox.sh; asserts nothing. */
#define _POSIX_C_SOURCE 200809L
#include "clsession.h"
#include "hostjit.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

int main(int argc, char **argv)
{
    int rounds = argc > 1 ? atoi(argv[1]) : 7;
    long count = argc > 2 ? atol(argv[2]) : 200000;
    if (rounds < 1 || rounds > 99 || count < 512 || count > 100000000) {
        fprintf(stderr, "usage: bench_hostjit [ROUNDS 1..99] [VALUES 512..1e8]\n");
        return 2;
    }
    char *header = clsession_kernel_source("brdf_models.h", NULL);
    char err[512];
    /* tests/test_usermodel_files/quad.cl's formula */
    struct hostjit *j = header ? hostjit_compile(header, "REAL brdf_user_eval(REAL c, REAL n, RSCALAR a, RSCALAR b)\n"
                                                 "{\n    REAL base = fmax((a * n + b) * (c - 1.0) + 1.0, 0.0);\n"
                                                 "    return base * base;\n}\n", err, sizeof err) : NULL;
    if (!j) {
        fprintf(stderr, "bench_hostjit: %s\n", header ? err : "kernels/brdf_models.h not found");
        return 3;
    }
    double *args = malloc((size_t)count * 4 * sizeof *args), *vals = malloc((size_t)count * sizeof *vals);
    double t_in[99], t_one[99], t_batch[99], sink = 0;
    for (long i = 0; i < count; ++i) {
        args[4 * i] = (double)(i % 1000) / 1000.0;
        args[4 * i + 1] = 2 + i % 500;
        args[4 * i + 2] = 0.448;
        args[4 * i + 3] = 0.099;
    }
    hostjit_fn fn = hostjit_function(j);
    hostjit_eval(j, 0.5, 2, 0.448, 0.099, &sink);   /* the child's start is not counted */
    for (int r = 0; r < rounds; ++r) {
        double t0 = now();
        for (long i = 0; i < count; ++i)
            sink += fn(args[4 * i], args[4 * i + 1], args[4 * i + 2], args[4 * i + 3]);
        double t1 = now();
        for (long i = 0; i < count; ++i) {
            double v;
            if (hostjit_eval(j, args[4 * i], args[4 * i + 1], args[4 * i + 2], args[4 * i + 3], &v) != 0)
                return 3;
            sink += v;
        }
        double t2 = now();
        if (hostjit_eval_many(j, args, (size_t)count, vals) != 0)
            return 3;
        double t3 = now();
        sink += vals[count / 2];
        t_in[r] = (t1 - t0) / (double)count * 1e9;
        t_one[r] = (t2 - t1) / (double)count * 1e9;
        t_batch[r] = (t3 - t2) / (double)count * 1e9;
    }
    qsort(t_in, (size_t)rounds, sizeof(double), cmp);
    qsort(t_one, (size_t)rounds, sizeof(double), cmp);
    qsort(t_batch, (size_t)rounds, sizeof(double), cmp);
    double a = t_in[rounds / 2], b = t_one[rounds / 2], c = t_batch[rounds / 2];
    printf("host reference, %ld values x %d rounds (medians, ns per value):\n", count, rounds);
    printf("  in this process (before the sandbox)   %10.1f\n", a);
    printf("  sandbox, one value per request          %10.1f   (%.1fx)\n", b, b / a);
    printf("  sandbox, batches of 512                 %10.1f   (%.1fx)\n", c, c / a);
    printf("(checksum %g)\n", sink);
    hostjit_free(j);
    free(header);
    free(args);
    free(vals);
    return 0;
}
