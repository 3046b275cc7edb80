/* bench_translate.c - the driver of scripts/bench_translate.sh: translates one shader file
 * (shaderlang_file, host/core/shader/shaderlang.h) REPEATS times and prints each translation's wall
 * time in seconds, one a line. Only the translation is timed: no compiler, no device. */
#define _POSIX_C_SOURCE 200809L
#include "shaderlang.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: bench_translate FILE REPEATS\n");
        return 2;
    }
    FILE *f = fopen(argv[1], "rb");
    if (!f) {
        perror(argv[1]);
        return 2;
    }
    static char text[1 << 20];
    size_t len = fread(text, 1, sizeof text, f);
    fclose(f);
    int repeats = atoi(argv[2]);
    for (int r = 0; r < repeats; ++r) {
        struct timespec a, b;
        char *out = NULL, err[600] = "";
        size_t outlen = 0;
        clock_gettime(CLOCK_MONOTONIC, &a);
        int rc = shaderlang_file(text, len, argv[1], &out, &outlen, err, sizeof err);
        clock_gettime(CLOCK_MONOTONIC, &b);
        free(out);
        if (rc != 0) {
            fprintf(stderr, "%s\n", err);
            return rc;
        }
        printf("%.6f %zu\n", (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec), outlen);
    }
    return 0;
}
