/* brdf_model_list.h - every built-in model, once. The enum of model ids, the device dispatch,
 * the rule of which models see only c, the host registry (ids, families, parameters,
 * references, formulas, descriptions, the default set) and the frontier's kind, operation
 * counts, default set and plot colour all come from these rows; nothing else lists the models.
 *
 * No include guard: the file is included once per use, with BRDF_MODEL defined by the includer:
 *   BRDF_MODEL(ENUM, C_ONLY, EVAL, FIELDS...)
 *   ENUM    the id is BRDF_<ENUM> (kernels/brdf_models.h makes the enum in this order);
 *   C_ONLY  1 when the formula takes c alone and not s = 1 - c (brdf_sees_only_c);
 *   EVAL    the formula as an expression of c, s = 1 - c, n, p0, p1 (kernels/brdf_models.h's
 *           dispatch returns it; the functions it calls are defined there);
 *   FIELDS  designated initialisers of struct model_info (host/core/models.h): the host reads
 *           them, the kernels drop them. Every row sets id, family, lobe, reference_id, formula,
 *           description, in_default_set, colour, kind and ops (tests/test_model_table.c checks).
 *   kind     MODEL_KIND_REFERENCE, _PAPER (the papers' models), _ENGINE (engines' cheap lobes),
 *            _TUNED (brdfbench's fitted families), _OTHER;
 *   ops      per evaluation: { counted, arithmetic, min/max/select, divides, transcendental calls,
 *            what is counted } as docs/frontier.md explains (counted 0: not a cheap lobe);
 *   frontier_rank  the position in the frontier's default set (0 or absent: not in it), and
 *            frontier_variants more specs of the model placed right after it there;
 *   colour   the plot colour by name (host/results/plots.c; "black" is a reference's).
 * A new model is one row here (its place decides its id) plus its functions in
 * kernels/brdf_models.h; docs/architecture.md has the recipe. */

BRDF_MODEL(PHONG, 0,
    brdf_pow_lobe_cs(c, s, n),
    .id = "phong", .family = MODEL_FAMILY_REFERENCE, .lobe = LOBE_PSI, .reference_id = "phong",
    .formula = "cos(psi)^n",
    .description = "Phong lobe: the reference of the Phong family",
    .in_default_set = 1, .colour = "black",
    .kind = MODEL_KIND_REFERENCE, .frontier_rank = 1,
    .ops = { 1, 1, 0, 0, 2, "exp(n log c)" })

BRDF_MODEL(BLINN, 0,
    brdf_pow_lobe_cs(c, s, n),
    .id = "blinn", .family = MODEL_FAMILY_REFERENCE, .lobe = LOBE_THETA_H, .reference_id = "blinn",
    .formula = "cos(theta_h)^n",
    .description = "Blinn-Phong lobe: the reference of the Blinn family",
    .in_default_set = 1, .colour = "black",
    .kind = MODEL_KIND_REFERENCE,
    .ops = { 1, 1, 0, 0, 2, "exp(n log c)" })

BRDF_MODEL(CQ2, 0,
    brdf_quadratic_s(s, n * RC(0.5)),
    .id = "cq2", .family = MODEL_FAMILY_QUADRATIC, .lobe = LOBE_PSI, .reference_id = "phong",
    .formula = "(n/2 (c-1) + 1)^2",
    .root = "c = 1 - 2/n",
    .description = "classic cosine-quadratic F2 (xi = 1/2)",
    .in_default_set = 1, .colour = "green",
    .kind = MODEL_KIND_PAPER, .frontier_rank = 3,
    .ops = { 1, 4, 1, 0, 0, "k = n/2; fma; max; square" })

BRDF_MODEL(FVOL, 0,
    brdf_quadratic_s(s, n * RC(0.463)),
    .id = "fvol", .family = MODEL_FAMILY_QUADRATIC, .lobe = LOBE_PSI, .reference_id = "phong",
    .formula = "(0.463 n (c-1) + 1)^2",
    .root = "c = 1 - 1/(0.463 n)",
    .description = "F_VOL of paper 1 (xi = 0.463)",
    .in_default_set = 1, .colour = "red",
    .kind = MODEL_KIND_PAPER, .frontier_rank = 4,
    .ops = { 1, 4, 1, 0, 0, "k = 0.463 n; fma; max; square" })

BRDF_MODEL(FVOL64, 0,
    brdf_quadratic_s(s, n * RC(29.0 / 64.0)),
    .id = "fvol64", .family = MODEL_FAMILY_QUADRATIC, .lobe = LOBE_PSI, .reference_id = "phong",
    .formula = "(29/64 n (c-1) + 1)^2",
    .root = "c = (29n - 64)/(29n)",
    .description = "paper 1's cheap variant, xi = 29/64",
    .in_default_set = 1, .colour = "purple",
    .kind = MODEL_KIND_PAPER, .frontier_rank = 5,
    .ops = { 1, 4, 1, 0, 0, "k = 29/64 n; fma; max; square" })

BRDF_MODEL(SCHLICK, 0,
    c / (n * s + c),
    .id = "schlick", .family = MODEL_FAMILY_RATIONAL, .lobe = LOBE_PSI, .reference_id = "phong",
    .formula = "c / (n - n c + c)",
    .description = "Schlick's rational approximation F_S",
    .in_default_set = 1, .colour = "brown",
    .kind = MODEL_KIND_PAPER, .frontier_rank = 6,
    .ops = { 1, 2, 0, 1, 0, "c / (n (1 - c) + c)" })

BRDF_MODEL(LYON, 0,
    brdf_lyon_s(s, n, (int)p0),
    .id = "lyon", .family = MODEL_FAMILY_QUADRATIC, .lobe = LOBE_PSI, .reference_id = "phong",
    .nparams = 1, .params = {
        { "k", 1, 16, 2, 1,
          "number of squarings; the exponent is 2^k" } },
    .formula = "(1 - n (1-c)/2^k)^(2^k)",
    .root = "c = 1 - 2^k/n",
    .description = "Lyon 1993, k squarings (k = 1 is cq2)",
    .in_default_set = 1, .colour = "pink",
    .kind = MODEL_KIND_PAPER, .frontier_rank = 7,
    .ops = { 1, 3, 1, 0, 0, "1 - n (1-c) 2^-k; max; plus k squarings" })

BRDF_MODEL(FQ, 0,
    brdf_quadratic_s(s, brdf_k_q(n, p0)),
    .id = "fq", .family = MODEL_FAMILY_QUADRATIC, .lobe = LOBE_PSI, .reference_id = "phong",
    .nparams = 1, .params = {
        { "Q", 1e-06, 0.999999, 0.64, 0,
          "level where f_Q equals c^n exactly" } },
    .formula = "(k_Q(n) (c-1) + 1)^2, k_Q(n) = (sqrt(Q) - 1)/(Q^(1/n) - 1)",
    .root = "c = 1 - 1/k_Q(n)",
    .description = "f_Q of paper 2",
    .in_default_set = 1, .colour = "grey",
    .kind = MODEL_KIND_PAPER, .frontier_rank = 8,
    .ops = { 1, 4, 1, 2, 3, "k_Q(n) = (sqrt Q - 1)/expm1(log Q / n); fma; max; square" })

BRDF_MODEL(FQ2, 0,
    brdf_quadratic_s(s, n * RC(0.448) + RC(0.099)),
    .id = "fq2", .family = MODEL_FAMILY_QUADRATIC, .lobe = LOBE_PSI, .reference_id = "phong",
    .formula = "((0.448 n + 0.099)(c-1) + 1)^2",
    .root = "c = (448n -901)/(448n + 99)",
    .description = "f_Q2 of paper 2: linear fit of k_Q(n)",
    .in_default_set = 1, .colour = "olive",
    .kind = MODEL_KIND_PAPER, .frontier_rank = 9,
    .ops = { 1, 4, 1, 0, 0, "k = fma(n, 0.448, 0.099); fma; max; square" })

BRDF_MODEL(FQ2N, 0,
    RC(0.214) * (RC(0.807) + n) * brdf_quadratic_s(s, n * RC(0.448) + RC(0.099)),
    .id = "fq2n", .family = MODEL_FAMILY_NORMALISED, .lobe = LOBE_PSI, .reference_id = "phongn",
    .formula = "0.214 (0.807 + n) ((0.448 n + 0.099)(c-1) + 1)^2",
    .root = "c = (448n - 901)/(448n + 99)",
    .description = "f_Q2 with paper 2's normalising coefficient",
    .in_default_set = 1, .colour = "cyan",
    .kind = MODEL_KIND_OTHER,
    .ops = { 0, 0, 0, 0, 0, "not counted: not a cheap lobe" })

BRDF_MODEL(PHONGN, 0,
    brdf_phong_norm(n) * brdf_pow_lobe_cs(c, s, n),
    .id = "phongn", .family = MODEL_FAMILY_NORMALISED, .lobe = LOBE_PSI, .reference_id = "phongn",
    .formula = "(n+2)/(2 pi) c^n",
    .description = "energy-normalised Phong (reference of fq2n)",
    .in_default_set = 1, .colour = "black",
    .kind = MODEL_KIND_OTHER,
    .ops = { 0, 0, 0, 0, 0, "not counted: not a cheap lobe" })

BRDF_MODEL(BLINNN, 0,
    brdf_blinn_norm(n) * brdf_pow_lobe_cs(c, s, n),
    .id = "blinnn", .family = MODEL_FAMILY_NORMALISED, .lobe = LOBE_THETA_H, .reference_id = "blinnn",
    .formula = "(n+2)(n+4) / (8 pi (2^(-n/2) + n)) c^n",
    .description = "energy-normalised Blinn-Phong (Giesen)",
    .in_default_set = 1, .colour = "black",
    .kind = MODEL_KIND_OTHER,
    .ops = { 0, 0, 0, 0, 0, "not counted: not a cheap lobe" })

BRDF_MODEL(BECKMANN, 0,
    brdf_d_beckmann_cs(c, s, brdf_alpha_from_n(n)),
    .id = "beckmann", .family = MODEL_FAMILY_MICROFACET, .lobe = LOBE_THETA_H, .reference_id = "phongn",
    .formula = "exp(-tan^2 / a^2) / (pi a^2 cos^4), a = sqrt(2/(n+2))",
    .description = "Beckmann distribution D against normalised Blinn-Phong D",
    .in_default_set = 1, .colour = "green",
    .kind = MODEL_KIND_OTHER,
    .ops = { 0, 0, 0, 0, 0, "not counted: not a cheap lobe" })

BRDF_MODEL(GGX, 0,
    brdf_d_ggx_cs(c, s, brdf_alpha_from_n(n)),
    .id = "ggx", .family = MODEL_FAMILY_MICROFACET, .lobe = LOBE_THETA_H, .reference_id = "phongn",
    .formula = "a^2 / (pi cos^4 (a^2 + tan^2)^2), a = sqrt(2/(n+2))",
    .description = "GGX distribution D against normalised Blinn-Phong D",
    .in_default_set = 1, .colour = "red",
    .kind = MODEL_KIND_OTHER,
    .ops = { 0, 0, 0, 0, 0, "not counted: not a cheap lobe" })

BRDF_MODEL(QUAD, 0,
    brdf_quadratic_s(s, n * p0 + p1),
    .id = "quad", .family = MODEL_FAMILY_QUADRATIC, .lobe = LOBE_PSI, .reference_id = "phong",
    .nparams = 2, .params = {
        { "a", 0, 10, 0.448, 0,
          "slope of k(n) = a n + b" },
        { "b", -10, 10, 0.099, 0,
          "offset of k(n) = a n + b" } },
    .formula = "((a n + b)(c-1) + 1)^2",
    .root = "c = 1 - 1/(a n + b)",
    .description = "the affine cosine-quadratic family (brdfbench fit)",
    .in_default_set = 0, .colour = "purple",
    .kind = MODEL_KIND_TUNED,
    .ops = { 1, 4, 1, 0, 0, "k = fma(n, a, b); fma; max; square" })

BRDF_MODEL(PHONGPOW, 1,
    pow(c, n),
    .id = "phongpow", .family = MODEL_FAMILY_REFERENCE, .lobe = LOBE_PSI, .reference_id = "phong",
    .formula = "cos(psi)^n through OpenCL's pow()",
    .description = "the Phong lobe through the pow() built-in: the literal pow()-based reference, for cost",
    .in_default_set = 1, .colour = "brown",
    .kind = MODEL_KIND_REFERENCE, .frontier_rank = 2,
    .ops = { 1, 0, 0, 0, 1, "pow(c, n), the built-in" })

BRDF_MODEL(SG, 0,
    brdf_gauss_lobe_s(s, n),
    .id = "sg", .family = MODEL_FAMILY_GAUSSIAN, .lobe = LOBE_PSI, .reference_id = "phong",
    .formula = "exp(n (c-1))",
    .description = "spherical Gaussian (Lagarde 2012, 'Spherical Gaussian approximation for Blinn-Phong, Phong and Fresnel'; engines write exp2(n/ln2 (c-1)))",
    .in_default_set = 0, .colour = "pink",
    .kind = MODEL_KIND_ENGINE, .frontier_rank = 10,
    .ops = { 1, 2, 0, 0, 1, "exp(n (c - 1))" })

BRDF_MODEL(UE4PHONG, 0,
    brdf_gauss_lobe_s(s, n + RC(0.775)),
    .id = "ue4phong", .family = MODEL_FAMILY_GAUSSIAN, .lobe = LOBE_PSI, .reference_id = "phong",
    .formula = "exp((n + 0.775)(c-1))",
    .description = "UE4 mobile PhongApprox (Karis 2014, 'Physically Based Shading on Mobile')",
    .in_default_set = 0, .colour = "grey",
    .kind = MODEL_KIND_ENGINE, .frontier_rank = 11,
    .ops = { 1, 3, 0, 0, 1, "exp((n + 0.775)(c - 1))" })

BRDF_MODEL(BG, 0,
    brdf_squarings_s(s, brdf_bg_a(n, 1 << (int)p0), (int)p0),
    .id = "bg", .family = MODEL_FAMILY_POWER, .lobe = LOBE_PSI, .reference_id = "phong",
    .nparams = 1, .params = {
        { "j", 1, 4, 1, 1,
          "squarings: the exponent is m = 2^j" } },
    .formula = "max(0, A c + 1 - A)^m, m = 2^j, A(n) = alpha_m n + beta_m",
    .root = "c = 1 - 1/A",
    .description = "Beaudoin and Guardado 2002 (ShaderX, 'A non-integer power function on the pixel shader'); A from the affine fit of their per-n bisection (kernels/brdf_models.h)",
    .in_default_set = 0, .colour = "olive",
    .kind = MODEL_KIND_ENGINE, .frontier_rank = 12, .frontier_variants = "bg:j=2",
    .ops = { 1, 3, 1, 0, 0, "A = fma(n, alpha, beta); fma; max; plus j squarings" })

BRDF_MODEL(KB, 0,
    brdf_kuijk_blake_s(s, brdf_kb_a(n), brdf_kb_b(n)),
    .id = "kb", .family = MODEL_FAMILY_ANGULAR, .lobe = LOBE_PSI, .reference_id = "phong",
    .formula = "alpha = acos c: 1 - alpha^2/(ab) below a, (alpha-b)^2/(b(b-a)) to b, 0 beyond; a = (n+5.6)/(n(0.09n+5.2)), b = (n+65)/(5n+31.7)",
    .root = "alpha = b",
    .description = "Kuijk and Blake 1989 (Computer Graphics Forum 8(4)), a and b as docs/definitions.md writes them",
    .in_default_set = 0, .colour = "cyan",
    .kind = MODEL_KIND_ENGINE, .frontier_rank = 13,
    .ops = { 1, 13, 4, 4, 2, "2 asin(sqrt(s/2)); a and b (2 divides); two pieces (2 divides); selects" })

BRDF_MODEL(KBSWAP, 0,
    brdf_kuijk_blake_s(s, brdf_kb_b(n), brdf_kb_a(n)),
    .id = "kbswap", .family = MODEL_FAMILY_ANGULAR, .lobe = LOBE_PSI, .reference_id = "phong",
    .formula = "kb with a and b exchanged, zeroed where negative",
    .root = "alpha = sqrt(ab)",
    .description = "Kuijk and Blake 1989 with a and b exchanged (Kuijk's later note on the print)",
    .in_default_set = 0, .colour = "blue",
    .kind = MODEL_KIND_ENGINE, .frontier_rank = 14,
    .ops = { 1, 13, 4, 4, 2, "2 asin(sqrt(s/2)); a and b (2 divides); two pieces (2 divides); selects" })

BRDF_MODEL(BITPOW, 0,
    brdf_bitpow(c, n),
    .id = "bitpow", .family = MODEL_FAMILY_BITS, .lobe = LOBE_PSI, .reference_id = "phong",
    .formula = "the float whose bits are n (bits(c) - bits(1)) + bits(1)",
    .root = "c^n < 2^-149",
    .description = "integer-bit pow (Schraudolph 1999 style); the host reproduces the bit arithmetic in double",
    .in_default_set = 0, .colour = "orange",
    .kind = MODEL_KIND_ENGINE, .frontier_rank = 15,
    .ops = { 1, 4, 1, 0, 0, "int subtract, convert, fma, max, convert" })

BRDF_MODEL(GAUSS, 0,
    brdf_gauss_lobe_s(s, n * p0 + p1),
    .id = "gauss", .family = MODEL_FAMILY_GAUSSIAN, .lobe = LOBE_PSI, .reference_id = "phong",
    .nparams = 2, .params = {
        { "a", 0, 10, 1, 0,
          "slope of k(n) = a n + b" },
        { "b", -10, 10, 0, 0,
          "offset of k(n) = a n + b" } },
    .formula = "exp((a n + b)(c-1))",
    .description = "the Gaussian family (brdfbench fit; sg is a=1,b=0, ue4phong a=1,b=0.775)",
    .in_default_set = 0, .colour = "green",
    .kind = MODEL_KIND_TUNED,
    .ops = { 1, 3, 0, 0, 1, "exp(fma(n, a, b)(c - 1))" })

BRDF_MODEL(CUBE, 0,
    brdf_cube_s(s, n * p0 + p1),
    .id = "pow3", .family = MODEL_FAMILY_POWER, .lobe = LOBE_PSI, .reference_id = "phong",
    .nparams = 2, .params = {
        { "a", 0, 10, 0.31, 0,
          "slope of k(n) = a n + b" },
        { "b", -10, 10, 0.1, 0,
          "offset of k(n) = a n + b" } },
    .formula = "((a n + b)(c-1) + 1)^3",
    .root = "c = 1 - 1/(a n + b)",
    .description = "the power family at m = 3 (brdfbench fit)",
    .in_default_set = 0, .colour = "red",
    .kind = MODEL_KIND_TUNED,
    .ops = { 1, 5, 1, 0, 0, "k = fma(n, a, b); fma; max; square; multiply" })

BRDF_MODEL(QUART, 0,
    brdf_fourth_s(s, n * p0 + p1),
    .id = "pow4", .family = MODEL_FAMILY_POWER, .lobe = LOBE_PSI, .reference_id = "phong",
    .nparams = 2, .params = {
        { "a", 0, 10, 0.237, 0,
          "slope of k(n) = a n + b" },
        { "b", -10, 10, 0.1, 0,
          "offset of k(n) = a n + b" } },
    .formula = "((a n + b)(c-1) + 1)^4",
    .root = "c = 1 - 1/(a n + b)",
    .description = "the power family at m = 4 (brdfbench fit)",
    .in_default_set = 0, .colour = "purple",
    .kind = MODEL_KIND_TUNED,
    .ops = { 1, 5, 1, 0, 0, "k = fma(n, a, b); fma; max; two squarings" })

BRDF_MODEL(CUBEFIT, 0,
    brdf_cube_s(s, n * RC(BRDF_CUBEFIT_A) + RC(BRDF_CUBEFIT_B)),
    .id = "pow3fit", .family = MODEL_FAMILY_POWER, .lobe = LOBE_PSI, .reference_id = "phong",
    .formula = "((A3 n + B3)(c-1) + 1)^3, constants in kernels/brdf_models.h",
    .root = "c = 1 - 1/(A3 n + B3)",
    .description = "cube fitted by brdfbench fit over n in [2, 1000] and frozen (docs/frontier.md)",
    .in_default_set = 0, .colour = "brown",
    .kind = MODEL_KIND_TUNED, .frontier_rank = 17,
    .ops = { 1, 5, 1, 0, 0, "k = fma(n, a, b); fma; max; square; multiply" })

BRDF_MODEL(QUARTFIT, 0,
    brdf_fourth_s(s, n * RC(BRDF_QUARTFIT_A) + RC(BRDF_QUARTFIT_B)),
    .id = "pow4fit", .family = MODEL_FAMILY_POWER, .lobe = LOBE_PSI, .reference_id = "phong",
    .formula = "((A4 n + B4)(c-1) + 1)^4, constants in kernels/brdf_models.h",
    .root = "c = 1 - 1/(A4 n + B4)",
    .description = "quart fitted by brdfbench fit over n in [2, 1000] and frozen (docs/frontier.md)",
    .in_default_set = 0, .colour = "pink",
    .kind = MODEL_KIND_TUNED, .frontier_rank = 18,
    .ops = { 1, 5, 1, 0, 0, "k = fma(n, a, b); fma; max; two squarings" })

BRDF_MODEL(GAUSSFIT, 0,
    brdf_gauss_lobe_s(s, n * RC(BRDF_GAUSSFIT_A) + RC(BRDF_GAUSSFIT_B)),
    .id = "gaussfit", .family = MODEL_FAMILY_GAUSSIAN, .lobe = LOBE_PSI, .reference_id = "phong",
    .formula = "exp((AG n + BG)(c-1)), constants in kernels/brdf_models.h",
    .description = "gauss fitted by brdfbench fit over n in [2, 1000] and frozen (docs/frontier.md)",
    .in_default_set = 0, .colour = "grey",
    .kind = MODEL_KIND_TUNED, .frontier_rank = 16,
    .ops = { 1, 3, 0, 0, 1, "exp(fma(n, a, b)(c - 1))" })

/* Physically based BRDFs f(N, L, V) (brdf_pb_eval). As lobes of one cosine they are the BRDF
   with the light at the normal and theta_h = acos(c) (brdf_pb_lobe); they are their own
   references and not part of the default set of the lobe commands. */
BRDF_MODEL(CT_BECKMANN, 0,
    brdf_pb_lobe(BRDF_CT_BECKMANN, c, n, p0, p1),
    .id = "ct-beckmann", .family = MODEL_FAMILY_PHYSICAL, .lobe = LOBE_THETA_H, .reference_id = "ct-beckmann",
    .nparams = 1, .params = {
        { "F0", 0, 1, 0.5, 0,
          "Schlick's Fresnel reflectance at normal incidence" } },
    .formula = "D F G / (4 N.L N.V): Beckmann D, Schlick F, Smith G (Walter's rational form), a = sqrt(2/(n+2))",
    .description = "Cook-Torrance in full with the Beckmann distribution (paper 1, eq. 7)",
    .in_default_set = 0, .colour = "black",
    .kind = MODEL_KIND_OTHER,
    .ops = { 0, 0, 0, 0, 0, "not counted: not a cheap lobe" })

BRDF_MODEL(CT_GGX, 0,
    brdf_pb_lobe(BRDF_CT_GGX, c, n, p0, p1),
    .id = "ct-ggx", .family = MODEL_FAMILY_PHYSICAL, .lobe = LOBE_THETA_H, .reference_id = "ct-ggx",
    .nparams = 1, .params = {
        { "F0", 0, 1, 0.5, 0,
          "Schlick's Fresnel reflectance at normal incidence" } },
    .formula = "D F G / (4 N.L N.V): GGX D, Schlick F, separable Smith G of GGX, a = sqrt(2/(n+2))",
    .description = "Cook-Torrance in full with GGX (Walter et al. 2007; paper 1, eq. 8)",
    .in_default_set = 0, .colour = "black",
    .kind = MODEL_KIND_OTHER,
    .ops = { 0, 0, 0, 0, 0, "not counted: not a cheap lobe" })

BRDF_MODEL(BRADY, 0,
    brdf_pb_lobe(BRDF_BRADY, c, n, p0, p1),
    .id = "brady", .family = MODEL_FAMILY_PHYSICAL, .lobe = LOBE_THETA_H, .reference_id = "brady",
    .nparams = 2, .params = {
        { "a", 0.01, 100, 1, 0,
          "lobe-shape parameter a of the printed form" },
        { "b", 0.01, 100, 1, 0,
          "lobe-shape parameter b of the printed form" } },
    .formula = "D G / (a^-2 b^-2 tan^2(theta_h) + 0.9994), Beckmann D and its Smith G at a(n)",
    .description = "Brady et al. 2014's metal BRDF as paper 2 prints it (the genBRDF original was not found; D and G are taken as Cook-Torrance's Beckmann pair)",
    .in_default_set = 0, .colour = "black",
    .kind = MODEL_KIND_OTHER,
    .ops = { 0, 0, 0, 0, 0, "not counted: not a cheap lobe" })

BRDF_MODEL(HE, 0,
    brdf_pb_lobe(BRDF_HE, c, n, p0, p1),
    .id = "he", .family = MODEL_FAMILY_PHYSICAL, .lobe = LOBE_THETA_H, .reference_id = "he",
    .nparams = 1, .params = {
        { "material", 0, 3, 0, 1,
          "preset: 0 rough aluminium, 1 polished aluminium, 2 gold, 3 plastic" } },
    .formula = "rho_sp + rho_dd + rho_ud of He, Torrance, Sillion, Greenberg 1991 (lambda, sigma0, tau, n + ik)",
    .description = "He et al. 1991 (Kirchhoff diffraction; the directional-diffuse sum truncated at float resolution)",
    .in_default_set = 0, .colour = "black",
    .kind = MODEL_KIND_OTHER,
    .ops = { 0, 0, 0, 0, 0, "not counted: not a cheap lobe" })

/* Terms of a microfacet BRDF (family term): lobes of the cosine c of the angle of incidence with
   L and V mirrored about N (H = N), against an exact term of their kind over (angle, n); n is the
   term's own axis (brdf_models.h, "terms of a microfacet BRDF"). At c = 0 L and V lie on the
   horizon, outside the BRDF's domain: the terms are 0 there, as a .brdf file's lobe is
   (host/core/shader/shaderlang_brdf.c) and the physical models' are. Not in the default sets. */
BRDF_MODEL(FRESNEL, 0,
    BRDF_SELECT(brdf_fresnel_dielectric(c, n), RSPLAT(0.0), c <= RC(0.0)),
    .id = "fresnel", .family = MODEL_FAMILY_TERM, .lobe = LOBE_THETA_H, .reference_id = "fresnel",
    .formula = "(g-c)^2/(2(g+c)^2) (1 + ((c(g+c)-1)/(c(g-c)+1))^2), g = sqrt(n^2 - 1 + c^2), n = index of refraction, c = L.H",
    .description = "exact Fresnel reflectance of unpolarised light at a dielectric (n: its index of refraction): the reference of Fresnel terms",
    .in_default_set = 0, .colour = "black",
    .kind = MODEL_KIND_REFERENCE,
    .ops = { 0, 0, 0, 0, 0, "not counted: not a cheap lobe" })

BRDF_MODEL(FRESNEL_SCHLICK, 0,
    BRDF_SELECT(brdf_fresnel_schlick_eta(s, n), RSPLAT(0.0), c <= RC(0.0)),
    .id = "fresnel-schlick", .family = MODEL_FAMILY_TERM, .lobe = LOBE_THETA_H, .reference_id = "fresnel",
    .formula = "F0 + (1 - F0)(1 - c)^5, F0 = ((n-1)/(n+1))^2, n = index of refraction, c = L.H",
    .description = "Schlick's approximation of the Fresnel reflectance, against the exact one",
    .in_default_set = 0, .colour = "blue",
    .kind = MODEL_KIND_OTHER,
    .ops = { 0, 0, 0, 0, 0, "not counted: not a cheap lobe" })

BRDF_MODEL(SMITH_GGX, 0,
    brdf_smith_ggx_separable(c, c, brdf_alpha_from_n(n)),
    .id = "smith-ggx", .family = MODEL_FAMILY_TERM, .lobe = LOBE_THETA_H, .reference_id = "smith-ggx-hc",
    .formula = "G1(c)^2, G1(x) = 2x/(x + sqrt(a^2 + (1-a^2)x^2)), a = sqrt(2/(n+2)), c = N.L = N.V (H = N)",
    .description = "separable Smith masking-shadowing of GGX, against the height-correlated form",
    .in_default_set = 0, .colour = "red",
    .kind = MODEL_KIND_OTHER,
    .ops = { 0, 0, 0, 0, 0, "not counted: not a cheap lobe" })

BRDF_MODEL(SMITH_GGX_HC, 0,
    brdf_smith_ggx_correlated(c, c, brdf_alpha_from_n(n)),
    .id = "smith-ggx-hc", .family = MODEL_FAMILY_TERM, .lobe = LOBE_THETA_H, .reference_id = "smith-ggx-hc",
    .formula = "1/(1 + 2 Lambda(c)), Lambda(x) = (sqrt(1 + a^2 tan^2)-1)/2, a = sqrt(2/(n+2)), c = N.L = N.V (H = N)",
    .description = "height-correlated Smith masking-shadowing of GGX (Heitz 2014): the reference of G terms",
    .in_default_set = 0, .colour = "black",
    .kind = MODEL_KIND_REFERENCE,
    .ops = { 0, 0, 0, 0, 0, "not counted: not a cheap lobe" })
