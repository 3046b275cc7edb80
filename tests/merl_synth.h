/* merl_synth.h - the tests' own MERL-format writer and the analytic BRDFs they write, written
 * here a second time from the format's description (issue 22, docs/measured.md) and the models'
 * definitions (docs/definitions.md), independent of host/core/merl.c and kernels/brdf_models.h.
 *
 * Cell centres: theta_h = ((i + 1/2)/90)^2 pi/2, theta_d = (j + 1/2)/90 pi/2,
 * phi_d = (k + 1/2)/180 pi (the inverse of the format's floor mapping, mid-cell). The
 * directions of a cell: H = (sin theta_h, 0, cos theta_h), D = (sin theta_d cos phi_d,
 * sin theta_d sin phi_d, cos theta_d), L = D rotated by theta_h about y, V = 2 (L.H) H - L. */
#ifndef BRDF_TEST_MERL_SYNTH_H
#define BRDF_TEST_MERL_SYNTH_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SYN_CELLS 1458000L

enum syn_kind { SYN_BLINN, SYN_CT_GGX, SYN_PATTERN };

struct syn_material {
    enum syn_kind kind;
    double n, ks, kd;           /* SYN_BLINN: ks cos(theta_h)^n + kd */
    double alpha, f0;           /* SYN_CT_GGX: kd + ks D F G / (4 N.L N.V) */
};

/* What a writer may break, for the malformed-file tests. */
struct syn_defects {
    int32_t dims[3];            /* 0,0,0: 90 90 180 */
    long trim;                  /* bytes left off the end (negative: bytes added) */
    long nan_cell;              /* -1, or the cell of the blue block set to NaN */
    long inf_cell;              /* -1, or the cell of the red block set to +Inf */
    int all_negative;           /* every value -1 */
    int neg_th_lo, neg_th_hi;   /* green cells with theta_h_i in [lo, hi) set to -1 (lo = hi: none) */
};

static inline void syn_defects_none(struct syn_defects *d)
{
    memset(d, 0, sizeof *d);
    d->nan_cell = d->inf_cell = -1;
}

static inline void syn_cell_dirs(long idx, double L[3], double V[3])
{
    int i = (int)(idx / (90 * 180)), j = (int)(idx / 180 % 90), k = (int)(idx % 180);
    double u = (i + 0.5) / 90, th = u * u * M_PI / 2, td = (j + 0.5) / 90 * M_PI / 2, pd = (k + 0.5) / 180 * M_PI;
    double D[3] = { sin(td) * cos(pd), sin(td) * sin(pd), cos(td) };
    L[0] = cos(th) * D[0] + sin(th) * D[2];
    L[1] = D[1];
    L[2] = -sin(th) * D[0] + cos(th) * D[2];
    double H[3] = { sin(th), 0, cos(th) };
    double lh = L[0] * H[0] + L[1] * H[1] + L[2] * H[2];
    for (int c = 0; c < 3; ++c)
        V[c] = 2 * lh * H[c] - L[c];
}

/* GGX Cook-Torrance written from the definitions: D = a^2 / (pi ((a^2 - 1) cos^2 + 1)^2),
 * Schlick F = F0 + (1 - F0)(1 - V.H)^5, Smith G1(x) = 2x / (x + sqrt(a^2 + (1 - a^2) x^2)). */
static inline double syn_ct_ggx(const double L[3], const double V[3], double alpha, double f0)
{
    double nl = L[2], nv = V[2];
    if (nl <= 0 || nv <= 0)
        return 0;
    double h[3] = { L[0] + V[0], L[1] + V[1], L[2] + V[2] };
    double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    double ch = h[2] / hl, vh = (V[0] * h[0] + V[1] * h[1] + V[2] * h[2]) / hl;
    double a2 = alpha * alpha;
    double den = (a2 - 1) * ch * ch + 1;
    double D = a2 / (M_PI * den * den);
    double F = f0 + (1 - f0) * pow(1 - vh, 5);
    double g1l = 2 * nl / (nl + sqrt(a2 + (1 - a2) * nl * nl));
    double g1v = 2 * nv / (nv + sqrt(a2 + (1 - a2) * nv * nv));
    return D * F * g1l * g1v / (4 * nl * nv);
}

/* The BRDF (sr^-1) of the material at cell idx; the same in every channel. */
static inline double syn_value(const struct syn_material *m, long idx)
{
    double L[3], V[3];
    syn_cell_dirs(idx, L, V);
    switch (m->kind) {
    case SYN_BLINN: {
        double h[3] = { L[0] + V[0], L[1] + V[1], L[2] + V[2] };
        double ch = h[2] / sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        return m->ks * pow(ch, m->n) + m->kd;
    }
    case SYN_CT_GGX:
        return m->kd + m->ks * syn_ct_ggx(L, V, m->alpha, m->f0);
    default:
        return (double)(idx % 997) + 0.25;   /* a pattern whose every cell differs from its neighbours */
    }
}

static const double syn_scale[3] = { 1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0 };

/* The value stored for channel c (the BRDF divided by the channel's scale); SYN_PATTERN stores
 * the pattern itself, plus c/8. */
static inline double syn_stored(const struct syn_material *m, int c, long idx)
{
    if (m->kind == SYN_PATTERN)
        return syn_value(m, idx) + c / 8.0;
    return syn_value(m, idx) / syn_scale[c];
}

static inline void syn_put_le(unsigned char *b, uint64_t u, int bytes)
{
    for (int i = 0; i < bytes; ++i)
        b[i] = (unsigned char)(u >> (8 * i));
}

/* Writes the file; 0, or -1 with perror. */
static inline int syn_write(const char *path, const struct syn_material *m, const struct syn_defects *d)
{
    size_t size = 12 + 3 * (size_t)SYN_CELLS * 8;
    unsigned char *buf = calloc(size + 64, 1);
    if (!buf)
        return -1;
    int32_t dims[3] = { 90, 90, 180 };
    if (d->dims[0] || d->dims[1] || d->dims[2])
        memcpy(dims, d->dims, sizeof dims);
    for (int i = 0; i < 3; ++i)
        syn_put_le(buf + 4 * i, (uint32_t)dims[i], 4);
    for (long idx = 0; idx < SYN_CELLS; ++idx) {
        double value = syn_value(m, idx);   /* once per cell: the channels differ only in scale */
        for (int c = 0; c < 3; ++c) {
            double v = m->kind == SYN_PATTERN ? value + c / 8.0 : value / syn_scale[c];
            if (d->all_negative)
                v = -1.0;
            int th = (int)(idx / (90 * 180));
            if (c == 1 && th >= d->neg_th_lo && th < d->neg_th_hi)
                v = -1.0;
            if (c == 2 && idx == d->nan_cell)
                v = NAN;
            if (c == 0 && idx == d->inf_cell)
                v = INFINITY;
            uint64_t u;
            memcpy(&u, &v, sizeof u);
            syn_put_le(buf + 12 + ((size_t)c * SYN_CELLS + (size_t)idx) * 8, u, 8);
        }
    }
    size_t len = (size_t)((long)size - d->trim);
    FILE *f = fopen(path, "wb");
    int ok = f && fwrite(buf, 1, len, f) == len;
    if (f && fclose(f) != 0)
        ok = 0;
    if (!ok)
        perror(path);
    free(buf);
    return ok ? 0 : -1;
}

#endif
