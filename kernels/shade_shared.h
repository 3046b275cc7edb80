/* shade_shared.h - what kernels/shade.cl and the image passes' host code (host/measure/render/,
 * host/support/raster.h) agree on, written once and included on both sides: the G-buffer's
 * planes, the shading modes, the positions in the float16 of shading parameters and the
 * display table's bins. Plain constants, no REAL. */
#ifndef BRDF_SHADE_SHARED_H
#define BRDF_SHADE_SHARED_H

/* The G-buffer's planes of floats, `stride` floats apart (host/support/raster.h fills them;
   shininess 0 marks background). */
enum gbuffer_plane { GB_PX, GB_PY, GB_PZ, GB_NX, GB_NY, GB_NZ, GB_SHIN, GB_NPLANES };

/* Shading modes: which cosine feeds the model and whether it is a microfacet D. */
#define SHADE_LOBE_PSI 0
#define SHADE_LOBE_THETA_H 1
#define SHADE_CT_BECKMANN 2 /* Cook-Torrance with the Smith G of the Beckmann distribution */
#define SHADE_CT_GGX 3      /* Cook-Torrance with the Smith G of GGX */
#define SHADE_PHYSICAL 4    /* a physically based BRDF of (N, L, V): brdf_pb_eval_ud */
#define SHADE_USER_FULL 5   /* a user full BRDF at the pixel's L, V, N: brdf_user_full */
#define SHADE_MEASURED 6    /* a measured material: the MERL table's luminance (merl_table) */

/* The shading parameters (a float16 by value): their positions. */
enum shade_param {
    SHADE_P_EYE = 0,         /* 0, 1, 2: the eye's position */
    SHADE_P_AMBIENT = 3,     /* ambient radiance */
    SHADE_P_LIGHT = 4,       /* 4, 5, 6: the light's unit direction towards it, or its position */
    SHADE_P_POINT = 7,       /* 1 for a point light (E = I / d^2), 0 for a directional one (E = I) */
    SHADE_P_INTENSITY = 8,   /* the light's intensity I */
    SHADE_P_KD = 9,
    SHADE_P_KS = 10,
    SHADE_P_F0 = 11,         /* Schlick's F0; 12..15 unused */
    SHADE_PARAMS = 16
};

/* Display table: bin of radiance x = (float bits >> 15) - DISPLAY_BIN0, clamped to
 * [0, DISPLAY_BINS - 1]; covers x in [2^-16, 2^8) (below: code 0, above: saturated). */
#define DISPLAY_MIN_EXP (-16)
#define DISPLAY_MAX_EXP 8
#define DISPLAY_BINS ((DISPLAY_MAX_EXP - DISPLAY_MIN_EXP) * 256)
#define DISPLAY_BIN0 ((127 + DISPLAY_MIN_EXP) << 8)

#endif
