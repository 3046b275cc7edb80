/*
 * throughput.cl - the cost of each model where shading pays it (docs/definitions.md, Throughput).
 *
 * A work-item evaluates TP_STREAMS independent float16 streams of inputs made in registers
 * from the work-item id and the loop counter, and sums the values, so that neither loads nor
 * stores hide the arithmetic. Explicit float16 is used because PoCL vectorises it to 512
 * bits and calls the vector forms of exp/log/pow, where a scalar kernel is vectorised to 256
 * bits at most and its scalar pow/exp calls are not vectorised at all. Several independent
 * streams keep the sums' add latency off the critical path.
 *
 * Inputs (the same in host/support/hostc_baseline.c, which times the same work in C):
 *   cosine   c = ((16 u + lane) + phase) * dc, then c += 64 dc per iteration, so one work-item
 *            sweeps c over [0, 1) (the cosine comes from a dot product in shading; every value
 *            of it occurs); phase = (gid mod 64) / 64 gives each work-item its own points;
 *   n        uniform: one value for the launch, as for one material; or
 *            varying: n = n_lo + (16 u + lane) dn_lane, then n += dn_step per iteration, a
 *            different shininess for every evaluation (per-pixel n), within [n_lo, n_hi].
 *
 * The host appends one line TP_MODEL_KERNELS(id) per model of a run: each model gets its own
 * kernels with the model id known at compile time, so brdf_eval's switch folds away as it
 * would in a shader specialised for its material. The pow() built-in gets the same kernels
 * (tp_*_pow): the reference cost each model is compared with.
 *
 * Kernels, for a model id or pow:
 *   tp_uniform_X (n, p0, p1, dc, iters, out)        sums of f over the generated inputs
 *   tp_varying_X (n_lo, dn_lane, dn_step, p0, p1, dc, iters, out)
 *   tp_points_X  (p0, p1, c[], n[], out[])           f at given points (accuracy checks)
 * out receives 16 partial sums per work-item.
 *
 * TP_W = 1 (-DTP_W=1, for a driver that vectorises across work-items itself and for which
 * sixteen-lane code is sixteen times the program: Mesa's llvmpipe, GPU compilers) writes the
 * same kernels in scalar float with a loop over the 16 lanes: the same inputs, rounded the
 * same way, and the same 16 sums per work-item. The physically based models' kernels are
 * float16 only.
 */
#ifndef TP_W
#define TP_W 16
#endif
#if TP_W == 16
#define REAL float16
#elif TP_W == 1
#define REAL float
#else
#error "TP_W must be 16 or 1"
#endif
#define RSCALAR float
#include "brdf_models.h"


#if TP_W == 1
#define TP_PHASE(gid) ((float)((gid) % 64) * (1.0f / 64.0f))
/* The cosine start of stream u and lane k: ((16 u + k) + phase) * dc, as the float16 form
   rounds it (the lane and 16 u are added first). */
#define TP_COS_START1(u, k, phase, dc) ((((float)(k) + (float)(16 * (u))) + (phase)) * (dc))

#define TP_UNIFORM_KERNEL(name, F)                                                              \
    __kernel void name(const float n_uniform, const float p0, const float p1, const float dc, \
                       const int iters, __global float *out)                                  \
    {                                                                                         \
        const int gid = (int)get_global_id(0);                                                \
        const float n = n_uniform;                                                            \
        const float dc_step = dc * (float)(16 * TP_STREAMS);                                  \
        const float phase = TP_PHASE(gid);                                                    \
        for (int k = 0; k < 16; ++k) {                                                        \
            float c0 = TP_COS_START1(0, k, phase, dc), c1 = TP_COS_START1(1, k, phase, dc);   \
            float c2 = TP_COS_START1(2, k, phase, dc), c3 = TP_COS_START1(3, k, phase, dc);   \
            float a0 = 0.0f, a1 = 0.0f, a2 = 0.0f, a3 = 0.0f;                                 \
            for (int i = 0; i < iters; ++i) {                                                 \
                a0 += F(c0, n, p0, p1);                                                       \
                a1 += F(c1, n, p0, p1);                                                       \
                a2 += F(c2, n, p0, p1);                                                       \
                a3 += F(c3, n, p0, p1);                                                       \
                c0 += dc_step;                                                                \
                c1 += dc_step;                                                                \
                c2 += dc_step;                                                                \
                c3 += dc_step;                                                                \
            }                                                                                 \
            out[16 * gid + k] = (a0 + a1) + (a2 + a3);                                        \
        }                                                                                     \
    }

#define TP_VARYING_KERNEL(name, F)                                                              \
    __kernel void name(const float n_lo, const float dn_lane, const float dn_step,             \
                       const float p0, const float p1, const float dc, const int iters,        \
                       __global float *out)                                                   \
    {                                                                                         \
        const int gid = (int)get_global_id(0);                                                \
        const float dc_step = dc * (float)(16 * TP_STREAMS);                                  \
        const float phase = TP_PHASE(gid);                                                    \
        for (int k = 0; k < 16; ++k) {                                                        \
            float c0 = TP_COS_START1(0, k, phase, dc), c1 = TP_COS_START1(1, k, phase, dc);   \
            float c2 = TP_COS_START1(2, k, phase, dc), c3 = TP_COS_START1(3, k, phase, dc);   \
            float n0 = fma((float)k, dn_lane, n_lo);                                          \
            float n1 = fma((float)k + 16.0f, dn_lane, n_lo);                                  \
            float n2 = fma((float)k + 32.0f, dn_lane, n_lo);                                  \
            float n3 = fma((float)k + 48.0f, dn_lane, n_lo);                                  \
            float a0 = 0.0f, a1 = 0.0f, a2 = 0.0f, a3 = 0.0f;                                 \
            for (int i = 0; i < iters; ++i) {                                                 \
                a0 += F(c0, n0, p0, p1);                                                      \
                a1 += F(c1, n1, p0, p1);                                                      \
                a2 += F(c2, n2, p0, p1);                                                      \
                a3 += F(c3, n3, p0, p1);                                                      \
                c0 += dc_step;                                                                \
                c1 += dc_step;                                                                \
                c2 += dc_step;                                                                \
                c3 += dc_step;                                                                \
                n0 += dn_step;                                                                \
                n1 += dn_step;                                                                \
                n2 += dn_step;                                                                \
                n3 += dn_step;                                                                \
            }                                                                                 \
            out[16 * gid + k] = (a0 + a1) + (a2 + a3);                                        \
        }                                                                                     \
    }

#define TP_POINTS_KERNEL(name, F)                                                               \
    __kernel void name(const float p0, const float p1, __global const float *c,                \
                       __global const float *n, __global float *out)                          \
    {                                                                                         \
        const size_t i = get_global_id(0);                                                    \
        for (size_t k = 16 * i; k < 16 * i + 16; ++k)                                         \
            out[k] = F(c[k], n[k], p0, p1);                                                   \
    }
#else
static float16 tp_lanes(void)
{
    return (float16)(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f,
                     8.0f, 9.0f, 10.0f, 11.0f, 12.0f, 13.0f, 14.0f, 15.0f);
}

/* The starting cosines of stream u: ((16 u + lane) + phase) * dc. The sum is exact (small
   integers plus a multiple of 1/64), so the host reproduces every input bit for bit. */
#define TP_COS_START(u, phase, dc) (((tp_lanes() + (float)(16 * (u))) + (phase)) * (dc))
#define TP_PHASE(gid) ((float)((gid) % 64) * (1.0f / 64.0f))

#define TP_UNIFORM_KERNEL(name, F)                                                              \
    __kernel void name(const float n_uniform, const float p0, const float p1, const float dc, \
                       const int iters, __global float *out)                                  \
    {                                                                                         \
        const int gid = (int)get_global_id(0);                                                \
        const float16 n = (float16)(n_uniform);                                               \
        const float dc_step = dc * (float)(16 * TP_STREAMS);                                  \
        const float phase = TP_PHASE(gid);                                                    \
        float16 c0 = TP_COS_START(0, phase, dc), c1 = TP_COS_START(1, phase, dc);             \
        float16 c2 = TP_COS_START(2, phase, dc), c3 = TP_COS_START(3, phase, dc);             \
        float16 a0 = (float16)(0.0f), a1 = a0, a2 = a0, a3 = a0;                              \
        for (int i = 0; i < iters; ++i) {                                                     \
            a0 += F(c0, n, p0, p1);                                                           \
            a1 += F(c1, n, p0, p1);                                                           \
            a2 += F(c2, n, p0, p1);                                                           \
            a3 += F(c3, n, p0, p1);                                                           \
            c0 += dc_step;                                                                    \
            c1 += dc_step;                                                                    \
            c2 += dc_step;                                                                    \
            c3 += dc_step;                                                                    \
        }                                                                                     \
        vstore16((a0 + a1) + (a2 + a3), gid, out);                                            \
    }

#define TP_VARYING_KERNEL(name, F)                                                              \
    __kernel void name(const float n_lo, const float dn_lane, const float dn_step,             \
                       const float p0, const float p1, const float dc, const int iters,        \
                       __global float *out)                                                   \
    {                                                                                         \
        const int gid = (int)get_global_id(0);                                                \
        const float dc_step = dc * (float)(16 * TP_STREAMS);                                  \
        const float phase = TP_PHASE(gid);                                                    \
        float16 c0 = TP_COS_START(0, phase, dc), c1 = TP_COS_START(1, phase, dc);             \
        float16 c2 = TP_COS_START(2, phase, dc), c3 = TP_COS_START(3, phase, dc);             \
        /* fma: one rounding, which the host reproduces with fmaf */                          \
        float16 n0 = fma(tp_lanes(), (float16)(dn_lane), (float16)(n_lo));                    \
        float16 n1 = fma(tp_lanes() + 16.0f, (float16)(dn_lane), (float16)(n_lo));            \
        float16 n2 = fma(tp_lanes() + 32.0f, (float16)(dn_lane), (float16)(n_lo));            \
        float16 n3 = fma(tp_lanes() + 48.0f, (float16)(dn_lane), (float16)(n_lo));            \
        float16 a0 = (float16)(0.0f), a1 = a0, a2 = a0, a3 = a0;                              \
        for (int i = 0; i < iters; ++i) {                                                     \
            a0 += F(c0, n0, p0, p1);                                                          \
            a1 += F(c1, n1, p0, p1);                                                          \
            a2 += F(c2, n2, p0, p1);                                                          \
            a3 += F(c3, n3, p0, p1);                                                          \
            c0 += dc_step;                                                                    \
            c1 += dc_step;                                                                    \
            c2 += dc_step;                                                                    \
            c3 += dc_step;                                                                    \
            n0 += dn_step;                                                                    \
            n1 += dn_step;                                                                    \
            n2 += dn_step;                                                                    \
            n3 += dn_step;                                                                    \
        }                                                                                     \
        vstore16((a0 + a1) + (a2 + a3), gid, out);                                            \
    }

#define TP_POINTS_KERNEL(name, F)                                                               \
    __kernel void name(const float p0, const float p1, __global const float *c,                \
                       __global const float *n, __global float *out)                          \
    {                                                                                         \
        const size_t i = get_global_id(0);                                                    \
        vstore16(F(vload16(i, c), vload16(i, n), p0, p1), i, out);                            \
    }

#endif

/* The three kernels of one model, its id a compile-time constant. */
#define TP_MODEL_KERNELS(id)                                                                   \
    static REAL tp_model_##id(REAL c, REAL n, float p0, float p1)                             \
    {                                                                                         \
        return brdf_eval(id, c, n, p0, p1);                                                   \
    }                                                                                         \
    TP_UNIFORM_KERNEL(tp_uniform_##id, tp_model_##id)                                         \
    TP_VARYING_KERNEL(tp_varying_##id, tp_model_##id)                                         \
    TP_POINTS_KERNEL(tp_points_##id, tp_model_##id)

/* The pow() built-in, the reference cost: c^n as a shader would write it. */
static REAL tp_pow_builtin(REAL c, REAL n, float p0, float p1)
{
    (void)p0;
    (void)p1;
    return pow(c, n);
}
TP_UNIFORM_KERNEL(tp_uniform_pow, tp_pow_builtin)
TP_VARYING_KERNEL(tp_varying_pow, tp_pow_builtin)
TP_POINTS_KERNEL(tp_points_pow, tp_pow_builtin)

/* TP_MODEL_KERNELS lines are appended by the host at the end of this file. */

#if TP_W == 16
/* ---- physically based models: the cost of an evaluation from the full vectors (N, L, V) ----
 *
 * A BRDF of N, L and V cannot be fed one cosine, so these kernels make three unit vectors per
 * evaluation in registers and evaluate the model from them, as a shader does: per lane
 *   N = normalize(x_N, y_N, 1), L = normalize(x_L, y_L, 1), V = normalize(x_V, y_V, 1)
 * with x, y ramps over the lanes and the work-item id, stepped every iteration, so every
 * evaluation sees new vectors. Each evaluation pays the three normalisations, the dot products
 * N.L, N.V, L.V and the model. The lobe models run in the same kernels, fed the cosine their
 * family uses (R.V = 2 (N.L)(N.V) - L.V, or N.H = (N.L + N.V) / |L + V|), so the rows compare
 * what a shader pays for each model from the same vectors.
 *
 * Kernels, per model id and lobe kind (0 psi, 1 theta_h, 2 physically based), appended by the
 * host as TP_VEC_MODEL_KERNELS(id, kind):
 *   tp_vec_X (n, p0, p1, step, iters, out)          sums of f over the generated vectors
 *   tp_vec_points_X (p0, p1, nl[], nv[], lv[], n[], out[])   f at given cosines (checks)
 * The pow() built-in: tp_vec_pow and tp_vec_points_pow (kind 3: pow(R.V, n)). */

static float16 tp_vec_eval(int id, int kind, float16 nl, float16 nv, float16 lv, float16 n, float p0, float p1)
{
    if (kind == 2)
        return brdf_pb_eval(id, nl, nv, lv, n, p0, p1);
    float16 c = kind == 1 ? (nl + nv) * rsqrt(fmax(2.0f + 2.0f * lv, 1e-12f)) : 2.0f * nl * nv - lv;
    float16 f = kind == 3 ? pow(fmax(c, 0.0f), n) : brdf_eval(id, c, n, p0, p1);
    /* the light and the viewer above the surface, as in shading */
    return select((float16)(0.0f), f, isgreater(nl, 0.0f) & isgreater(nv, 0.0f));
}

static float16 tp_vec_dot_unit(float16 ax, float16 ay, float16 bx, float16 by, float16 ainv, float16 binv)
{
    return (ax * bx + ay * by + 1.0f) * ainv * binv;
}

#define TP_VEC_STREAM(a, xn, yn, xl, yl, xv, yv, n, id, kind, p0, p1)                           \
    do {                                                                                        \
        float16 in_ = rsqrt(xn * xn + yn * yn + 1.0f);                                          \
        float16 il_ = rsqrt(xl * xl + yl * yl + 1.0f);                                          \
        float16 iv_ = rsqrt(xv * xv + yv * yv + 1.0f);                                          \
        float16 nl_ = tp_vec_dot_unit(xn, yn, xl, yl, in_, il_);                                \
        float16 nv_ = tp_vec_dot_unit(xn, yn, xv, yv, in_, iv_);                                \
        float16 lv_ = tp_vec_dot_unit(xl, yl, xv, yv, il_, iv_);                                \
        a += tp_vec_eval(id, kind, nl_, nv_, lv_, n, p0, p1);                                   \
    } while (0)

/* Two independent streams per work-item (the physically based models are long enough that
   two hide the sums' latency); the ramps: x_N in [-0.3, 0.3], x_L in [-1, 0.2], x_V in
   [-0.2, 1], y small, so most pairs are lit and the highlight is crossed. */
#define TP_VEC_KERNEL(name, id, kind) TP_VEC_KERNEL_OF(name, id, kind, TP_VEC_STREAM, )
#define TP_VEC_KERNEL_OF(name, id, kind, STREAM, EXTRA_ARGS)                                     \
    __kernel void name(const float n_uniform, const float p0, const float p1, const float step,  \
                       const int iters, __global float *out EXTRA_ARGS)                         \
    {                                                                                           \
        const int gid = (int)get_global_id(0);                                                  \
        const float16 n = (float16)(n_uniform);                                                 \
        const float phase = TP_PHASE(gid);                                                      \
        float16 t0 = (tp_lanes() + phase) * (1.0f / 16.0f), t1 = t0 + (0.5f / 16.0f);           \
        float16 a0 = (float16)(0.0f), a1 = a0;                                                  \
        for (int i = 0; i < iters; ++i) {                                                       \
            float16 xn0 = 0.6f * t0 - 0.3f, xl0 = -1.0f + 1.2f * t0, xv0 = 1.0f - 1.2f * t0;    \
            float16 xn1 = 0.6f * t1 - 0.3f, xl1 = -1.0f + 1.2f * t1, xv1 = 1.0f - 1.2f * t1;    \
            float16 y0 = 0.1f * t0 - 0.05f, y1 = 0.1f * t1 - 0.05f;                             \
            STREAM(a0, xn0, y0, xl0, -y0, xv0, 0.5f * y0, n, id, kind, p0, p1);                 \
            STREAM(a1, xn1, y1, xl1, -y1, xv1, 0.5f * y1, n, id, kind, p0, p1);                 \
            t0 = t0 + step;                                                                     \
            t1 = t1 + step;                                                                     \
            t0 = t0 - floor(t0);                                                                \
            t1 = t1 - floor(t1);                                                                \
        }                                                                                       \
        vstore16(a0 + a1, gid, out);                                                            \
    }

#define TP_VEC_POINTS_KERNEL(name, id, kind)                                                     \
    __kernel void name(const float p0, const float p1, __global const float *nl,               \
                       __global const float *nv, __global const float *lv,                     \
                       __global const float *n, __global float *out)                           \
    {                                                                                           \
        const size_t i = get_global_id(0);                                                      \
        vstore16(tp_vec_eval(id, kind, vload16(i, nl), vload16(i, nv), vload16(i, lv),          \
                             vload16(i, n), p0, p1), i, out);                                   \
    }

#define TP_VEC_MODEL_KERNELS(id, kind)                                                           \
    TP_VEC_KERNEL(tp_vec_##id, id, kind)                                                         \
    TP_VEC_POINTS_KERNEL(tp_vec_points_##id, id, kind)

TP_VEC_KERNEL(tp_vec_pow, 0, 3)
TP_VEC_POINTS_KERNEL(tp_vec_points_pow, 0, 3)

/* ---- full BRDFs that take the vectors themselves: a user full BRDF (kind 4: a GLSL/HLSL
 * function of L, V, N or a BRDF Explorer file, brdf_user_full) and a measured material (kind 5:
 * the MERL table, a float buffer in the file's layout). The same generated vectors as above,
 * normalised, and the result zeroed where L or V lies below the surface, as for the lobes.
 * A lookup pays the half/difference angles (two atan2, a sqrt and a rotation per lane) and
 * three loads from a 17.5 MB table: memory traffic, where the other rows pay arithmetic.
 *   tp_full_K (n, p0, p1, step, iters, out, table)
 *   tp_full_points_K (p0, p1, planes[10 x count: Lxyz Vxyz Nxyz n], count, out[], table) */
static float16 tp_full_eval(int kind, float16 lx, float16 ly, float16 lz, float16 vx, float16 vy, float16 vz,
                            float16 nx, float16 ny, float16 nz, float16 n, float p0, float p1,
                            __global const float *table)
{
    float16 f = (float16)(0.0f);
#ifdef BRDF_HAVE_USER_FULL
    if (kind == 4)
        f = brdf_user_full(lx, ly, lz, vx, vy, vz, nx, ny, nz, n, p0, p1);
#endif
    if (kind == 5)
        f = brdf_merl_lookup16(table, lx, ly, lz, vx, vy, vz, nx, ny, nz);
    float16 nl = nx * lx + ny * ly + nz * lz, nv = nx * vx + ny * vy + nz * vz;
    return select((float16)(0.0f), f, isgreater(nl, 0.0f) & isgreater(nv, 0.0f));
}

#define TP_FULL_STREAM(a, xn, yn, xl, yl, xv, yv, n, id, kind, p0, p1)                          \
    do {                                                                                        \
        float16 in_ = rsqrt(xn * xn + yn * yn + 1.0f);                                          \
        float16 il_ = rsqrt(xl * xl + yl * yl + 1.0f);                                          \
        float16 iv_ = rsqrt(xv * xv + yv * yv + 1.0f);                                          \
        a += tp_full_eval(kind, xl * il_, yl * il_, il_, xv * iv_, yv * iv_, iv_, xn * in_,     \
                          yn * in_, in_, n, p0, p1, table);                                     \
    } while (0)

#define TP_TABLE_ARG , __global const float *table
#define TP_FULL_MODEL_KERNELS(kind)                                                              \
    TP_VEC_KERNEL_OF(tp_full_##kind, 0, kind, TP_FULL_STREAM, TP_TABLE_ARG)                      \
    __kernel void tp_full_points_##kind(const float p0, const float p1, __global const float *g,  \
                                        const uint count, __global float *out,                  \
                                        __global const float *table)                            \
    {                                                                                           \
        const size_t i = get_global_id(0);                                                      \
        vstore16(tp_full_eval(kind, vload16(i, g), vload16(i, g + count),                       \
                              vload16(i, g + 2 * count), vload16(i, g + 3 * count),             \
                              vload16(i, g + 4 * count), vload16(i, g + 5 * count),             \
                              vload16(i, g + 6 * count), vload16(i, g + 7 * count),             \
                              vload16(i, g + 8 * count), vload16(i, g + 9 * count), p0, p1,     \
                              table), i, out);                                                  \
    }

#endif

/* TP_MODEL_KERNELS and TP_VEC_MODEL_KERNELS lines follow, appended by the host. */
