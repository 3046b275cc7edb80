/* merl.c - the MERL reader, the half/difference conversion and the table lookup in double, and
 * the device lookup of kernels/merl.cl (merl.h). */
#include "merl.h"

#include "exitcodes.h"
#include "infile.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define REAL double
#define RSCALAR double
#include "brdf_models.h"
#undef REAL
#undef RSCALAR

_Static_assert(BRDF_MERL_CELLS == MERL_CELLS, "merl.h and brdf_models.h agree on the table's size");

const double merl_channel_scale[3] = { BRDF_MERL_SCALE_R, BRDF_MERL_SCALE_G, BRDF_MERL_SCALE_B };
static const char *const channel_name[3] = { "red", "green", "blue" };

static uint32_t le32(const unsigned char *b)
{
    return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
}

static double le_double(const unsigned char *b)
{
    uint64_t u = 0;
    for (int i = 7; i >= 0; --i)
        u = u << 8 | b[i];
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

static void material_name(const char *path, char *name, size_t len)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    size_t n = strlen(base);
    if (n > 7 && strcmp(base + n - 7, ".binary") == 0)
        n -= 7;
    snprintf(name, len, "%.*s", (int)(n < len ? n : len - 1), base);
    /* a control character of a file name (a newline, ESC) never reaches a terminal, a table
       or a heading as it is, nor a '|': measured.json's readers take a name with one for a
       broken table cell (compare_check.c) */
    for (char *p = name; *p; ++p)
        if ((unsigned char)*p < 0x20 || *p == 0x7f || *p == '|')
            *p = '?';
}

/* Reads up to cap bytes of f into buf; the count read. */
static size_t read_all(FILE *f, unsigned char *buf, size_t cap)
{
    size_t got = 0;
    while (got < cap) {
        size_t r = fread(buf + got, 1, cap - got, f);
        if (r == 0)
            break;
        got += r;
    }
    return got;
}

int merl_read(const char *path, struct merl_material *m, char *err, size_t errlen)
{
    memset(m, 0, sizeof *m);
    /* A regular file only: a FIFO, /dev/stdin or a device would block or flood the read
       (infile.h). */
    char why[256];
    int fd = infile_open(path, 0, NULL, why, sizeof why);
    FILE *f = fd >= 0 ? fdopen(fd, "rb") : NULL;
    if (!f) {
        if (fd >= 0)
            close(fd);
        snprintf(err, errlen, "%s: cannot open: %s (expected a MERL .binary file)", path,
                 fd >= 0 ? strerror(errno) : why);
        return EXIT_USAGE;
    }
    struct stat st;
    long long file_size = -1;
    if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode))
        file_size = (long long)st.st_size;
    else if (fstat(fileno(f), &st) == 0 && S_ISDIR(st.st_mode)) {
        fclose(f);
        snprintf(err, errlen, "%s: is a folder (expected a MERL .binary file)", path);
        return EXIT_USAGE;
    }
    int rc = EXIT_USAGE;
    unsigned char head[12];
    unsigned char *body = NULL;
    size_t got = read_all(f, head, sizeof head);
    if (got < sizeof head) {
        snprintf(err, errlen, "%s: short file: %zu bytes, a MERL file starts with three 32-bit dimensions and "
                 "holds %ld bytes", path, got, MERL_FILE_BYTES);
        goto done;
    }
    uint32_t dims[3] = { le32(head), le32(head + 4), le32(head + 8) };
    if (dims[0] != MERL_TH || dims[1] != MERL_TD || dims[2] != MERL_PD) {
        /* The dimensions are said only where they look like a table's: the first bytes of
           another kind of file (a text, a key) never reach the message, or a CI log. */
        if (dims[0] >= 1 && dims[0] <= 100000 && dims[1] >= 1 && dims[1] <= 100000 && dims[2] >= 1 &&
            dims[2] <= 100000)
            snprintf(err, errlen, "%s: dimensions %d %d %d (expected 90 90 180, product 1458000)", path,
                     (int32_t)dims[0], (int32_t)dims[1], (int32_t)dims[2]);
        else
            snprintf(err, errlen, "%s: not a MERL file: it does not begin with three table dimensions (expected "
                     "90 90 180, product 1458000)", path);
        goto done;
    }
    size_t body_bytes = (size_t)(MERL_FILE_BYTES - 12);
    body = malloc(body_bytes + 1);
    m->value = malloc(3 * (size_t)MERL_CELLS * sizeof *m->value);
    if (!body || !m->value) {
        snprintf(err, errlen, "%s: out of memory for the table (%ld bytes)", path, MERL_FILE_BYTES);
        rc = EXIT_RUNTIME;
        goto done;
    }
    got = read_all(f, body, body_bytes + 1);
    if (ferror(f)) {
        snprintf(err, errlen, "%s: read error: %s", path, strerror(errno));
        goto done;
    }
    if (got != body_bytes) {
        long long total = file_size >= 0 ? file_size : (long long)(12 + got);
        if (got < body_bytes)
            snprintf(err, errlen, "%s: size %lld bytes, %lld short of the %ld that dimensions 90 90 180 need "
                     "(12 + 3 x 1458000 x 8)", path, total, (long long)MERL_FILE_BYTES - total, MERL_FILE_BYTES);
        else if (file_size >= 0)
            snprintf(err, errlen, "%s: size %lld bytes, %lld more than the %ld that dimensions 90 90 180 need "
                     "(12 + 3 x 1458000 x 8)", path, total, total - (long long)MERL_FILE_BYTES, MERL_FILE_BYTES);
        else
            snprintf(err, errlen, "%s: more than the %ld bytes that dimensions 90 90 180 need (12 + 3 x 1458000 x 8)",
                     path, MERL_FILE_BYTES);
        goto done;
    }
    for (int c = 0; c < 3; ++c) {
        double *out = m->value + (size_t)c * MERL_CELLS;
        const unsigned char *in = body + (size_t)c * MERL_CELLS * 8;
        for (long i = 0; i < MERL_CELLS; ++i) {
            double v = le_double(in + 8 * i);
            if (!isfinite(v)) {
                snprintf(err, errlen, "%s: the %s block's cell %ld (theta_h %ld, theta_d %ld, phi_d %ld) is %s", path,
                         channel_name[c], i, i / (MERL_TD * MERL_PD), i / MERL_PD % MERL_TD, i % MERL_PD,
                         isnan(v) ? "NaN" : (v > 0 ? "+Inf" : "-Inf"));
                goto done;
            }
            /* The device holds the table in float: a cell beyond float's range would be +Inf
               there, and every figure made of it inf or NaN. */
            if (!(fabs(v * merl_channel_scale[c]) <= FLT_MAX)) {
                snprintf(err, errlen, "%s: the %s block's cell %ld (theta_h %ld, theta_d %ld, phi_d %ld) is %.3g, "
                         "beyond float's range once scaled (accepted: |value x %g| <= %.4g)", path,
                         channel_name[c], i, i / (MERL_TD * MERL_PD), i / MERL_PD % MERL_TD, i % MERL_PD, v,
                         merl_channel_scale[c], (double)FLT_MAX);
                goto done;
            }
            if (v < 0)
                m->negative[c]++;
            out[i] = v * merl_channel_scale[c];
        }
    }
    for (long i = 0; i < MERL_CELLS; ++i)
        if (m->value[i] < 0 || m->value[MERL_CELLS + i] < 0 || m->value[2 * MERL_CELLS + i] < 0)
            m->unmeasured++;
    if (m->unmeasured == MERL_CELLS) {
        snprintf(err, errlen, "%s: every cell is negative in at least one channel (no cell was measured)", path);
        goto done;
    }
    snprintf(m->path, sizeof m->path, "%s", path);
    material_name(path, m->name, sizeof m->name);
    rc = 0;
done:
    free(body);
    fclose(f);
    if (rc)
        merl_free(m);
    return rc;
}

void merl_free(struct merl_material *m)
{
    free(m->value);
    memset(m, 0, sizeof *m);
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

void merl_half_diff(const double L[3], const double V[3], const double N[3], double *theta_h, double *theta_d,
                    double *phi_d)
{
    brdf_merl_half_diff_n(L[0], L[1], L[2], V[0], V[1], V[2], N[0], N[1], N[2], theta_h, theta_d, phi_d);
}

long merl_index(double theta_h, double theta_d, double phi_d, int *ith, int *itd, int *ipd)
{
    int i, j, k;
    long idx = brdf_merl_index3(theta_h, theta_d, phi_d, &i, &j, &k);
    if (ith)
        *ith = i;
    if (itd)
        *itd = j;
    if (ipd)
        *ipd = k;
    return idx;
}

void merl_cell_centre(int ith, int itd, int ipd, double *theta_h, double *theta_d, double *phi_d)
{
    double u = (ith + 0.5) / MERL_TH;
    *theta_h = u * u * (M_PI / 2);
    *theta_d = (itd + 0.5) / MERL_TD * (M_PI / 2);
    *phi_d = (ipd + 0.5) / MERL_PD * M_PI;
}

void merl_dirs(double theta_h, double theta_d, double phi_d, double L[3], double V[3])
{
    double D[3] = { sin(theta_d) * cos(phi_d), sin(theta_d) * sin(phi_d), cos(theta_d) };
    double ct = cos(theta_h), st = sin(theta_h);
    /* L = D rotated by +theta_h about y (the inverse of brdf_merl_half_diff's rotation) */
    L[0] = D[0] * ct + D[2] * st;
    L[1] = D[1];
    L[2] = -D[0] * st + D[2] * ct;
    double H[3] = { st, 0, ct };
    double lh = dot3(L, H);
    for (int i = 0; i < 3; ++i)
        V[i] = 2 * lh * H[i] - L[i];
}

int merl_cell(const struct merl_material *m, long idx, double rgb[3])
{
    int measured = 1;
    for (int c = 0; c < 3; ++c) {
        rgb[c] = m->value[(size_t)c * MERL_CELLS + (size_t)idx];
        if (rgb[c] < 0)
            measured = 0;
    }
    return measured;
}

int merl_lookup(const struct merl_material *m, const double L[3], const double V[3], const double N[3],
                double rgb[3])
{
    double th, td, pd;
    merl_half_diff(L, V, N, &th, &td, &pd);
    return merl_cell(m, merl_index(th, td, pd, NULL, NULL, NULL), rgb);
}

double merl_luminance(const struct merl_material *m, const double L[3], const double V[3], const double N[3])
{
    double rgb[3];
    merl_lookup(m, L, V, N, rgb);
    return brdf_merl_luminance(rgb[0], rgb[1], rgb[2]);
}

int merl_table_buffer(struct cl_session *s, const struct merl_material *m, cl_mem *out)
{
    size_t table_bytes = 3 * (size_t)MERL_CELLS * sizeof(float);
    *out = NULL;
    if (table_bytes > s->max_alloc) {
        fprintf(stderr, "brdfbench: %s: the %zu-byte table exceeds the device's allocation limit (%llu bytes)\n",
                m->name, table_bytes, (unsigned long long)s->max_alloc);
        return EXIT_RUNTIME;
    }
    float *table = malloc(table_bytes);
    if (!table) {
        fprintf(stderr, "brdfbench: %s: out of memory for the device table\n", m->name);
        return EXIT_RUNTIME;
    }
    for (size_t i = 0; i < 3 * (size_t)MERL_CELLS; ++i)
        table[i] = (float)m->value[i];
    int rc = 0;
    cl_int e;
    *out = clCreateBuffer(s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, table_bytes, table, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(merl table)", done);
done:
    free(table);
    return rc;
}

int merl_eval_device(struct cl_session *s, const struct merl_material *m, const float *L, const float *V,
                     size_t count, float *rgb, int *index)
{
    int rc = 0;
    cl_int e;
    cl_program program = NULL;
    cl_kernel kernel = NULL;
    cl_mem buf[5] = { NULL, NULL, NULL, NULL, NULL };
    static const char *const names[] = { "merl_lookup" };
    cl_kernel *const kernels[] = { &kernel };
    size_t table_bytes = 3 * (size_t)MERL_CELLS * sizeof(float);
    if (count == 0)
        return 0;
    if (count > (size_t)UINT32_MAX || count > SIZE_MAX / (3 * sizeof(float)) ||
        3 * count * sizeof(float) > s->max_alloc || table_bytes > s->max_alloc) {
        fprintf(stderr, "brdfbench: merl lookup: %zu points or the %zu-byte table exceed the device's allocation "
                "limit (%llu bytes)\n", count, table_bytes, (unsigned long long)s->max_alloc);
        return EXIT_RUNTIME;
    }
    rc = clsession_build_kernels(s, "merl.cl", NULL, "", &program, 1, names, kernels);
    if (rc || (rc = merl_table_buffer(s, m, &buf[0])) != 0)
        goto done;
    buf[1] = clCreateBuffer(s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, 3 * count * sizeof(float), (void *)L, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(merl L)", done);
    buf[2] = clCreateBuffer(s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, 3 * count * sizeof(float), (void *)V, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(merl V)", done);
    buf[3] = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, 3 * count * sizeof(float), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(merl rgb)", done);
    buf[4] = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, count * sizeof(int), NULL, &e);
    CL_CHECK_ERR_GOTO(e, "clCreateBuffer(merl cell)", done);
    cl_uint n = (cl_uint)count;
    CL_SET_ARGS_GOTO(done, kernel, 0, CL_ARG(buf[0]), CL_ARG(buf[1]), CL_ARG(buf[2]), CL_ARG(n), CL_ARG(buf[3]),
                     CL_ARG(buf[4]));
    size_t global = (count + 63) / 64 * 64;
    rc = clsession_launch(s, kernel, 1, &global, NULL, m->name, NULL);
    if (rc)
        goto done;
    CL_CHECK_GOTO(clEnqueueReadBuffer(s->queue, buf[3], CL_TRUE, 0, 3 * count * sizeof(float), rgb, 0, NULL, NULL),
                  done);
    CL_CHECK_GOTO(clEnqueueReadBuffer(s->queue, buf[4], CL_TRUE, 0, count * sizeof(int), index, 0, NULL, NULL), done);
done:
    for (int i = 4; i >= 0; --i)
        if (buf[i])
            clReleaseMemObject(buf[i]);
    clsession_release_kernels(&program, 1, kernels);
    return rc;
}
