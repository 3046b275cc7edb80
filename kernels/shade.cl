/*
 * shade.cl - the full-image shading pass of `brdfbench render`, and the copy kernel that
 * moves the same bytes per pixel (the memory-bound ceiling the shading is compared with).
 *
 * Input: the G-buffer as planes of floats (px py pz nx ny nz shininess, `stride` floats
 * apart; shininess 0 marks background). Output per pixel: RGBA8 (packed little-endian in
 * a uint) and the linear specular radiance as a float (the quantity the error images
 * compare). 28 bytes in, 8 bytes out per pixel.
 *
 * Each work-item owns a contiguous run of pixels and walks it sixteen at a time with
 * float16 values: PoCL 3.1 turns explicit float16 into 512-bit code and calls the vector
 * forms of pow/exp, while it neither vectorises scalar pow/exp nor goes past 256 bits when
 * it vectorises scalar code across work-items. One launch shape serves every image size
 * (the pixel count is an argument), so PoCL compiles each kernel once.
 *
 * Shading (per pixel; E = irradiance from the light at normal incidence):
 *   specular radiance  L_s = E (N.L) ks S, with
 *       S = f(c, n), c = R.V (psi, Phong family) or N.H (theta_h, Blinn family), or
 *       S = D F G / (4 (N.L)(N.V)) for Cook-Torrance: D the model, Schlick F, the
 *           separable Smith G that belongs to D (Beckmann or GGX), or
 *       S = the BRDF of a physically based model (brdf_pb_eval_ud, without He's
 *           uniform-diffuse term: the pass adds its own diffuse term), or
 *       S = a user full BRDF at the pixel's L, V, N (brdf_user_full: a GLSL/HLSL function of
 *           vectors or a BRDF Explorer file, luminance), or
 *       S = a measured material's luminance, the cell of the MERL table holding (L, V) about N
 *           (brdf_merl_lookup16: a lookup, its cost memory traffic)
 *   radiance           L = E (N.L) kd + ambient + L_s              (white light)
 * The material is tinted: display colour channel k = sRGB8(1 - exp(-exposure tint_k L)),
 * i.e. diffuse and specular reflectance both scaled by the tint (a coloured metal). One
 * scalar radiance per pixel then needs one table look-up for its display colour instead
 * of three transcendental tone curves, which would cost more than most models do.
 * The table (built by the host, host/measure/render/render.c) is indexed by the float's exponent and 8
 * leading mantissa bits: relative bins of 2^-8, within one 8-bit code of the exact curve.
 * The double-precision host reference (host/measure/render/render.c) recomputes both outputs on a sample.
 */
#define REAL float16
#define RSCALAR float
#include "brdf_models.h"
/* the G-buffer's planes, the shading modes, the parameters' positions, the display table */
#include "shade_shared.h"

#define BACKGROUND_RGBA 0xff2a2620u /* sRGB (32, 38, 42), opaque */

/* params (float16 by value): the positions of shade_shared.h's enum shade_param */

static uint16 display_lookup(__global const uint *table, float16 x)
{
    int16 i = clamp((as_int16(x) >> 15) - DISPLAY_BIN0, 0, DISPLAY_BINS - 1);
    /* LLVM turns these sixteen loads into one 512-bit gather */
    return (uint16)(table[i.s0], table[i.s1], table[i.s2], table[i.s3], table[i.s4],
                    table[i.s5], table[i.s6], table[i.s7], table[i.s8], table[i.s9],
                    table[i.sa], table[i.sb], table[i.sc], table[i.sd], table[i.se],
                    table[i.sf]);
}

__kernel void shade(__global const float *gbuf, const uint stride, const uint nchunks,
                    __global uint *out_rgba, __global float *out_spec, const int mode,
                    const int model, const float p0, const float p1, const float16 params,
                    __global const uint *display_table, __global const float *merl_table)
{
    const uint nitems = (uint)get_global_size(0);
    const uint gid = (uint)get_global_id(0);
    /* contiguous runs of 16-pixel chunks, one per work-item */
    const uint per = (nchunks + nitems - 1) / nitems;
    const uint c0 = min(gid * per, nchunks);
    const uint c1 = min(c0 + per, nchunks);

    __global const float *gpx = gbuf + GB_PX * (size_t)stride;
    __global const float *gpy = gbuf + GB_PY * (size_t)stride;
    __global const float *gpz = gbuf + GB_PZ * (size_t)stride;
    __global const float *gnx = gbuf + GB_NX * (size_t)stride;
    __global const float *gny = gbuf + GB_NY * (size_t)stride;
    __global const float *gnz = gbuf + GB_NZ * (size_t)stride;
    __global const float *gsh = gbuf + GB_SHIN * (size_t)stride;

    float pa[SHADE_PARAMS];   /* the parameters by position */
    vstore16(params, 0, pa);
    const float eye_x = pa[SHADE_P_EYE], eye_y = pa[SHADE_P_EYE + 1], eye_z = pa[SHADE_P_EYE + 2];
    const float light_x = pa[SHADE_P_LIGHT], light_y = pa[SHADE_P_LIGHT + 1], light_z = pa[SHADE_P_LIGHT + 2];
    const float intensity = pa[SHADE_P_INTENSITY];
    const float ambient = pa[SHADE_P_AMBIENT];
    const int point_light = pa[SHADE_P_POINT] > 0.5f;
    const float kd = pa[SHADE_P_KD], ks = pa[SHADE_P_KS], f0 = pa[SHADE_P_F0];

    for (uint ch = c0; ch < c1; ++ch) {
        float16 px = vload16(ch, gpx), py = vload16(ch, gpy), pz = vload16(ch, gpz);
        float16 nx = vload16(ch, gnx), ny = vload16(ch, gny), nz = vload16(ch, gnz);
        float16 n = vload16(ch, gsh);
        int16 fg = isgreater(n, 0.0f);

        /* V: towards the eye */
        float16 vx = eye_x - px, vy = eye_y - py, vz = eye_z - pz;
        float16 vinv = rsqrt(vx * vx + vy * vy + vz * vz);
        vx *= vinv;
        vy *= vinv;
        vz *= vinv;

        /* L: towards the light; e: irradiance at normal incidence */
        float16 lx, ly, lz, e;
        if (point_light) {
            lx = light_x - px;
            ly = light_y - py;
            lz = light_z - pz;
            float16 d2 = lx * lx + ly * ly + lz * lz;
            float16 linv = rsqrt(d2);
            lx *= linv;
            ly *= linv;
            lz *= linv;
            e = intensity / d2;
        } else {
            lx = (float16)light_x;
            ly = (float16)light_y;
            lz = (float16)light_z;
            e = (float16)intensity;
        }
        float16 ndotl = nx * lx + ny * ly + nz * lz;
        float16 ndotv = nx * vx + ny * vy + nz * vz;

        float16 ldotv = lx * vx + ly * vy + lz * vz;
        float16 c, s;
        if (mode == SHADE_LOBE_PSI) {
            /* c = R.V with R = 2 (N.L) N - L */
            c = 2.0f * ndotl * ndotv - ldotv;
            s = brdf_eval(model, c, n, p0, p1);
        } else {
            /* H = (L + V) / |L + V|, |L + V| = sqrt(2 + 2 L.V): c = N.H without forming H */
            float16 hinv = rsqrt(fmax(2.0f + 2.0f * ldotv, 1e-30f));
            c = (ndotl + ndotv) * hinv;
            if (mode == SHADE_PHYSICAL)
                s = brdf_pb_eval_ud(model, ndotl, ndotv, ldotv, n, p0, p1, 0.0f);
#ifdef BRDF_HAVE_USER_FULL
            else if (mode == SHADE_USER_FULL)
                s = brdf_user_full(lx, ly, lz, vx, vy, vz, nx, ny, nz, n, p0, p1);
#endif
            else if (mode == SHADE_MEASURED)
                s = brdf_merl_lookup16(merl_table, lx, ly, lz, vx, vy, vz, nx, ny, nz);
            else
                s = brdf_eval(model, c, n, p0, p1);
            if (mode == SHADE_CT_BECKMANN || mode == SHADE_CT_GGX) {
                /* V.H = (1 + L.V) / |L + V| */
                float16 vdoth = fmax((1.0f + ldotv) * hinv, 0.0f);
                float16 m = 1.0f - vdoth;
                float16 m2 = m * m;
                float16 fresnel = f0 + (1.0f - f0) * (m2 * m2 * m);
                float16 alpha = brdf_alpha_from_n(n);
                float16 nl = fmax(ndotl, 1e-6f), nv = fmax(ndotv, 1e-6f);
                float16 masking =
                    mode == SHADE_CT_GGX
                        ? brdf_smith_g1_ggx(nl, alpha) * brdf_smith_g1_ggx(nv, alpha)
                        : brdf_smith_g1_beckmann(nl, alpha) * brdf_smith_g1_beckmann(nv, alpha);
                s = s * fresnel * masking / (4.0f * nl * nv);
            }
        }
        /* lit: in front of the light, and the lobe's cosine inside the model's domain
           [0, 1]; Cook-Torrance also needs the viewer above the surface */
        int16 lit = fg & isgreater(ndotl, 0.0f) & isgreater(c, 0.0f);
        if (mode >= SHADE_CT_BECKMANN)
            lit &= isgreater(ndotv, 0.0f);
        float16 spec = select((float16)0.0f, e * ndotl * ks * s, lit);
        float16 radiance = e * fmax(ndotl, 0.0f) * kd + ambient + spec;

        uint16 rgba = display_lookup(display_table, radiance);
        rgba = select((uint16)BACKGROUND_RGBA, rgba, as_uint16(fg));
        vstore16(rgba, ch, out_rgba);
        vstore16(spec, ch, out_spec);
    }
}

/* The same bytes as `shade` (seven planes in, a uint and a float out per pixel) with one
 * add per value: the rate shading would reach if its arithmetic were free. */
__kernel void copy_gbuffer(__global const float *gbuf, const uint stride, const uint nchunks,
                           __global uint *out_rgba, __global float *out_spec)
{
    const uint nitems = (uint)get_global_size(0);
    const uint gid = (uint)get_global_id(0);
    const uint per = (nchunks + nitems - 1) / nitems;
    const uint c0 = min(gid * per, nchunks);
    const uint c1 = min(c0 + per, nchunks);
    for (uint ch = c0; ch < c1; ++ch) {
        float16 a = vload16(ch, gbuf) + vload16(ch, gbuf + stride) +
                    vload16(ch, gbuf + 2 * (size_t)stride);
        float16 b = vload16(ch, gbuf + 3 * (size_t)stride) +
                    vload16(ch, gbuf + 4 * (size_t)stride) +
                    vload16(ch, gbuf + 5 * (size_t)stride);
        float16 n = vload16(ch, gbuf + 6 * (size_t)stride);
        vstore16(as_uint16(a + b), ch, out_rgba);
        vstore16(a + n, ch, out_spec);
    }
}
