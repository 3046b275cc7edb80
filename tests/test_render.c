/* test_render.c - the image passes: sphere pixels whose normal is known in closed form shade
 * on the device to the values worked out here and to the double reference; cq2 at n = 2,
 * which is the Phong lobe there, shades as Phong does; a small render_run writes the
 * reference's zero error, cq2's non-zero error and fq2's smaller mean error (docs/definitions.md: fq2's max delta 1.256%
 * and max Delta 0.128 against cq2's 7.924% and 0.162); bad scene files fail with their
 * file and line and leave the previous results as they were. */
#include "check.h"
#include "clsession.h"
#include "jsonr.h"
#include "raster.h"
#include "render.h"
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define PI 3.14159265358979323846

static double dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static void unit(double *a)
{
    double l = sqrt(dot(a, a));
    for (int c = 0; c < 3; c++)
        a[c] /= l;
}

static char tmpdir[256];

/* One sphere (1 x 1 grid) filling a 64 x 64 frame. raster.h's layout: cells 1 high, the
   sphere of radius 0.42 at the origin, the camera at (0, 0, 4) looking down -z with the
   frame at z = 0 exactly one cell high, so tan(fov/2) = 0.5 / 4. */
static void test_sphere_pixels(struct cl_session *s)
{
    const int W = 64, H = 64;
    double shin = 64.0;
    struct gbuffer g;
    struct camera cam;
    char err[512];
    if (gbuffer_alloc(&g, W, H, err, sizeof err) != 0 ||
        raster_spheres(&g, 1, 1, &shin, &cam, err, sizeof err) != 0) {
        CHECK(0, "sphere G-buffer: %s", err);
        return;
    }
    struct render_options o;
    render_options_default(&o);
    struct render_device dev;
    int rc = render_device_open(&dev, s, &o, err, sizeof err);
    CHECK(rc == 0, "render_device_open: %s", err);
    if (rc) {
        gbuffer_free(&g);
        return;
    }
    cl_int e;
    cl_mem gbuf = clCreateBuffer(s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                 g.stride * GB_NPLANES * sizeof(float), g.data, &e);
    cl_mem orgba = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, g.stride * 4, NULL, &e);
    cl_mem ospec = clCreateBuffer(s->ctx, CL_MEM_WRITE_ONLY, g.stride * 4, NULL, &e);
    unsigned *rgba = malloc(g.npix * sizeof *rgba);
    float *spec = malloc(g.npix * sizeof *spec);

    /* light from the upper right front, directional, E = 1; a dielectric F0 so that the
       Fresnel term's angle dependence shows (V.H = 0.886 at the test pixel) */
    struct render_light lt = {{0, 0, 4}, {0.6, 0.5, 0.6}, 0, 1.0};
    o.f0 = 0.04;
    unit(lt.light);
    const int px = 40, py = 22;
    /* the pixel's ray, written out here: x right, y up, forward -z */
    double t = 0.5 / 4.0;
    double dir[3] = {(2.0 * (px + 0.5) / W - 1.0) * t, (1.0 - 2.0 * (py + 0.5) / H) * t, -1.0};
    unit(dir);
    /* |eye + s dir|^2 = r^2, nearer root */
    double b = dot(lt.eye, dir), cc = dot(lt.eye, lt.eye) - 0.42 * 0.42;
    double sroot = -b - sqrt(b * b - cc);
    double P[3], N[3], V[3], L[3] = {lt.light[0], lt.light[1], lt.light[2]};
    for (int k = 0; k < 3; k++) {
        P[k] = lt.eye[k] + sroot * dir[k];
        N[k] = P[k] / 0.42;
        V[k] = -dir[k];
    }
    size_t pi = (size_t)py * W + px;
    CHECK(fabs(gbuffer_plane(&g, GB_NX)[pi] - N[0]) < 1e-6 &&
              fabs(gbuffer_plane(&g, GB_NY)[pi] - N[1]) < 1e-6 &&
              fabs(gbuffer_plane(&g, GB_NZ)[pi] - N[2]) < 1e-6,
          "G-buffer normal (%g %g %g), closed form (%g %g %g)", gbuffer_plane(&g, GB_NX)[pi],
          gbuffer_plane(&g, GB_NY)[pi], gbuffer_plane(&g, GB_NZ)[pi], N[0], N[1], N[2]);
    double nl = dot(N, L), nv = dot(N, V);
    CHECK(nl > 0.3 && nv > 0.3, "test pixel must face light and eye (N.L %g, N.V %g)", nl, nv);

    /* Phong: R = 2 (N.L) N - L, spec = E (N.L) ks (R.V)^n */
    double R[3], H2[3];
    for (int k = 0; k < 3; k++) {
        R[k] = 2.0 * nl * N[k] - L[k];
        H2[k] = L[k] + V[k];
    }
    unit(H2);
    double want_phong = nl * o.ks * pow(dot(R, V), 64.0);
    /* Blinn: spec = E (N.L) ks (N.H)^n */
    double want_blinn = nl * o.ks * pow(dot(N, H2), 64.0);
    /* Cook-Torrance with GGX (docs/definitions.md): alpha = sqrt(2 / (n + 2)),
       D = alpha^2 / (pi ((N.H)^2 (alpha^2 - 1) + 1)^2), F = F0 + (1 - F0)(1 - V.H)^5,
       G = G1(N.L) G1(N.V), G1(x) = 2x / (x + sqrt(alpha^2 + (1 - alpha^2) x^2));
       spec = E (N.L) ks D F G / (4 (N.L)(N.V)) */
    double a2 = 2.0 / 66.0, ch = dot(N, H2), vh = dot(V, H2);
    double dg = a2 / (PI * pow(ch * ch * (a2 - 1.0) + 1.0, 2));
    double fr = o.f0 + (1.0 - o.f0) * pow(1.0 - vh, 5);
    double g1l = 2 * nl / (nl + sqrt(a2 + (1 - a2) * nl * nl));
    double g1v = 2 * nv / (nv + sqrt(a2 + (1 - a2) * nv * nv));
    double want_ggx = o.ks * dg * fr * g1l * g1v / (4.0 * nv);

    const struct {
        const char *model;
        double want;
    } cases[] = {{"phong", want_phong}, {"blinn", want_blinn}, {"ggx", want_ggx}};
    for (int k = 0; k < 3; k++) {
        struct model_spec m;
        model_spec_parse(cases[k].model, &m, err, sizeof err);
        int mode = render_shading_mode(&m);
        rc = render_device_shade(&dev, gbuf, g.stride, g.npix, orgba, ospec, &m, mode, &lt, &o,
                                 rgba, spec, NULL);
        CHECK(rc == 0, "%s: device shading failed", cases[k].model);
        if (rc)
            continue;
        /* float G-buffer and float shading: relative 1e-4 covers n = 64 times a few ulps of
           the cosine, while a wrong vector or factor is off by far more */
        double rel = fabs(spec[pi] - cases[k].want) / cases[k].want;
        CHECK(rel < 1e-4, "%s pixel: device %.9g, closed form %.9g (rel %.2g)", cases[k].model,
              spec[pi], cases[k].want, rel);
        double pos[3] = {gbuffer_plane(&g, GB_PX)[pi], gbuffer_plane(&g, GB_PY)[pi],
                         gbuffer_plane(&g, GB_PZ)[pi]};
        double nrm[3] = {gbuffer_plane(&g, GB_NX)[pi], gbuffer_plane(&g, GB_NY)[pi],
                         gbuffer_plane(&g, GB_NZ)[pi]};
        double ref_spec, ref_rad;
        render_shade_ref(&m, mode, &lt, &o, pos, nrm, 64.0, &ref_spec, &ref_rad);
        rel = fabs(ref_spec - cases[k].want) / cases[k].want;
        CHECK(rel < 1e-4, "%s pixel: double reference %.9g, closed form %.9g", cases[k].model,
              ref_spec, cases[k].want);
        /* radiance = E (N.L) kd + ambient + spec; the device's colour within one code of
           the exact display curve at that radiance */
        double rad = nl * o.kd + o.ambient + cases[k].want;
        unsigned char exact[3];
        render_display_exact(&o, rad, exact);
        int worst = 0;
        for (int c = 0; c < 3; c++) {
            int d = abs((int)((rgba[pi] >> (8 * c)) & 255u) - (int)exact[c]);
            worst = d > worst ? d : worst;
        }
        CHECK(worst <= 1, "%s pixel colour off the exact display curve by %d codes",
              cases[k].model, worst);
    }
    /* a background pixel (corner) carries no specular radiance */
    CHECK(spec[0] == 0.0f, "background specular %g, expected 0", spec[0]);

    /* cq2 at n = 2 is (1 (c - 1) + 1)^2 = c^2, the Phong lobe at n = 2 (docs/definitions.md), and both
       read the same psi: on a G-buffer of shininess 2 the two shade every pixel alike, up to
       float rounding of c^2 against exp(2 ln c) (a few ulps of the peak). */
    struct model_spec cq2, phong;
    model_spec_parse("cq2", &cq2, err, sizeof err);
    model_spec_parse("phong", &phong, err, sizeof err);
    CHECK(render_shading_mode(&cq2) == render_shading_mode(&phong), "cq2 and phong read the same cosine");
    struct gbuffer g2;
    struct camera cam2;
    double shin2 = 2.0;
    float *spec2 = malloc(g.npix * sizeof *spec2);
    if (gbuffer_alloc(&g2, W, H, err, sizeof err) != 0 ||
        raster_spheres(&g2, 1, 1, &shin2, &cam2, err, sizeof err) != 0 || !spec2) {
        CHECK(0, "G-buffer of shininess 2: %s", err);
    } else {
        cl_mem gbuf2 = clCreateBuffer(s->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                      g2.stride * GB_NPLANES * sizeof(float), g2.data, &e);
        CHECK(e == CL_SUCCESS, "G-buffer of shininess 2 on the device (%d)", (int)e);
        int rc1 = render_device_shade(&dev, gbuf2, g2.stride, g2.npix, orgba, ospec, &phong,
                                      render_shading_mode(&phong), &lt, &o, rgba, spec, NULL);
        int rc2 = render_device_shade(&dev, gbuf2, g2.stride, g2.npix, orgba, ospec, &cq2,
                                      render_shading_mode(&cq2), &lt, &o, rgba, spec2, NULL);
        CHECK(rc1 == 0 && rc2 == 0, "shading phong and cq2 at n = 2 (rc %d, %d)", rc1, rc2);
        double peak = 0, worst = 0;
        size_t lit = 0;
        for (size_t i = 0; i < g2.npix; i++) {
            peak = spec[i] > peak ? spec[i] : peak;
            lit += spec[i] > 0;
        }
        for (size_t i = 0; i < g2.npix; i++) {
            double d = fabs((double)spec2[i] - (double)spec[i]);
            if (!isnan(worst) && !(d <= worst))   /* a NaN stays the worst */
                worst = d;
        }
        CHECK(lit > 100 && worst <= 1e-5 * peak,
              "cq2 vs phong at n = 2: largest difference %.3g of a peak %.3g (%zu lit pixels)",
              worst, peak, lit);
        if (gbuf2)
            clReleaseMemObject(gbuf2);
        gbuffer_free(&g2);
    }
    free(spec2);

    free(rgba);
    free(spec);
    clReleaseMemObject(ospec);
    clReleaseMemObject(orgba);
    clReleaseMemObject(gbuf);
    render_device_close(&dev);
    gbuffer_free(&g);
}

/* Finds scenes[i] with "scene" == name and its "models" entry for model. */
static const struct jr_value *find_model(const struct jr_doc *d, const char *scene,
                                         const char *model)
{
    const struct jr_value *scenes = jr_get(&d->root, "scenes");
    for (size_t i = 0; scenes && i < scenes->count; i++) {
        const struct jr_value *sc = &scenes->items[i], *name = jr_get(sc, "scene");
        if (!name || name->type != JR_STR || strcmp(name->str, scene) != 0)
            continue;
        const struct jr_value *models = jr_get(sc, "models");
        for (size_t k = 0; models && k < models->count; k++) {
            const struct jr_value *m = jr_get(&models->items[k], "model");
            if (m && m->type == JR_STR && strcmp(m->str, model) == 0)
                return &models->items[k];
        }
    }
    return NULL;
}

static double metric(const struct jr_value *model, const char *key)
{
    const struct jr_value *mt = model ? jr_get(model, "metrics") : NULL;
    const struct jr_value *v = mt ? jr_get(mt, key) : NULL;
    return v && v->type == JR_NUM ? v->num : NAN;
}

static int check_within(const struct jr_value *model)
{
    const struct jr_value *c = model ? jr_get(model, "double_reference_check") : NULL;
    const struct jr_value *v = c ? jr_get(c, "within_bound") : NULL;
    return v && v->type == JR_BOOL && v->num == 1;
}

static void test_render_run(struct cl_session *s)
{
    char err[1024] = "", out[512], path[700];
    snprintf(out, sizeof out, "%s/run", tmpdir);
    /* small scene files: one flat patch as the teapot, a cube as the bunny */
    char teapot[600], cube[600], bad[600];
    snprintf(teapot, sizeof teapot, "%s/flat.inc", tmpdir);
    snprintf(cube, sizeof cube, "%s/cube.obj", tmpdir);
    snprintf(bad, sizeof bad, "%s/bad.obj", tmpdir);
    test_write_file(teapot, "bicubic_patch { type 1\n"
                       " <0,0,0> <1,0,0> <2,0,0> <3,0,0>\n <0,1,0> <1,1,0.5> <2,1,0.5> <3,1,0>\n"
                       " <0,2,0> <1,2,0.5> <2,2,0.5> <3,2,0>\n <0,3,0> <1,3,0> <2,3,0> <3,3,0>\n}\n");
    test_write_file(cube, "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\n"
                     "v -1 1 1\nf 5 6 7 8\nf 1 4 3 2\nf 2 3 7 6\nf 1 5 8 4\nf 4 8 7 3\nf 1 2 6 5\n");
    test_write_file(bad, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n");

    struct render_options o;
    render_options_default(&o);
    o.io = (struct engine_io){ out, 1 };
    o.width = 240;
    o.height = 144;
    o.ntime_sizes = 0;
    o.teapot_path = teapot;
    o.bunny_path = cube;
    o.tess = 4;
    o.nmodels = model_spec_list_parse("phong,cq2,fq2", o.models, RENDER_MAX_MODELS, err,
                                      sizeof err);
    struct render_result rr;
    int rc = render_run(s, &o, &rr);
    render_result_free(&rr);
    CHECK(rc == 0, "render_run: rc %d: %s", rc, rr.err);
    if (rc)
        return;
    snprintf(path, sizeof path, "%s/render.json", out);
    struct jr_doc d;
    rc = jr_parse_file(path, &d, err, sizeof err);
    CHECK(rc == 0, "render.json: %s", err);
    if (rc)
        return;
    const struct jr_value *phong = find_model(&d, "spheres", "phong");
    const struct jr_value *cq2 = find_model(&d, "spheres", "cq2");
    const struct jr_value *fq2 = find_model(&d, "spheres", "fq2");
    CHECK(phong && cq2 && fq2, "spheres: models missing from render.json");
    /* phong is its own reference: the same kernel on the same inputs */
    CHECK(metric(phong, "max_abs") == 0.0 && metric(phong, "pixels") > 100,
          "phong against itself: max error %g over %g pixels", metric(phong, "max_abs"),
          metric(phong, "pixels"));
    {
        /* present and null, not merely absent (metric() reads an absent key as NaN too) */
        const struct jr_value *mt = phong ? jr_get(phong, "metrics") : NULL;
        const struct jr_value *psnr = mt ? jr_get(mt, "psnr_db") : NULL;
        CHECK(psnr && psnr->type == JR_NULL, "identical images: PSNR must be null (infinite)");
    }
    CHECK(metric(cq2, "max_abs") > 0.01, "cq2 max error %g, expected clearly non-zero",
          metric(cq2, "max_abs"));
    CHECK(metric(fq2, "mean_abs") < metric(cq2, "mean_abs"),
          "fq2 mean error %g should be below cq2's %g", metric(fq2, "mean_abs"),
          metric(cq2, "mean_abs"));
    CHECK(check_within(phong) && check_within(cq2) && check_within(fq2),
          "spheres: a model outside the double-reference bound");
    CHECK(check_within(find_model(&d, "teapot", "cq2")) &&
              check_within(find_model(&d, "bunny", "fq2")),
          "mesh scenes: missing or outside the double-reference bound");
    CHECK(metric(find_model(&d, "bunny", "phong"), "pixels") > 100,
          "the cube covers %g pixels", metric(find_model(&d, "bunny", "phong"), "pixels"));
    jr_free(&d);
    struct stat st;
    snprintf(path, sizeof path, "%s/render/spheres/contact.png", out);
    CHECK(stat(path, &st) == 0 && st.st_size > 1000, "%s missing", path);
    snprintf(path, sizeof path, "%s/render/teapot/cq2_error.png", out);
    CHECK(stat(path, &st) == 0 && st.st_size > 100, "%s missing", path);

    /* A malformed bunny file: exit 2 naming the file and line; the earlier results stay. */
    size_t len0 = 0, len1 = 0;
    snprintf(path, sizeof path, "%s/render.json", out);
    char *before = test_read_file(path, &len0);
    o.bunny_path = bad;
    rc = render_run(s, &o, &rr);
    render_result_free(&rr);
    char want[700];
    snprintf(want, sizeof want, "%s:4:", bad);
    CHECK(rc == 2 && strstr(rr.err, want) != NULL, "malformed OBJ: rc %d, message '%s'", rc, rr.err);
    char *after = test_read_file(path, &len1);
    CHECK(before && after && len0 == len1 && memcmp(before, after, len0) == 0,
          "a failed run changed render.json");
    free(before);
    free(after);
    snprintf(path, sizeof path, "%s/render/teapot/cq2.png", out);
    CHECK(stat(path, &st) == 0, "a failed run removed the previous pictures");
    char cmd[800];
    snprintf(cmd, sizeof cmd, "ls -a '%s' | grep -c render- >/dev/null", out);
    CHECK(system(cmd) != 0, "a staging folder was left behind in %s", out);

    /* a missing scene file given by the user */
    o.bunny_path = "/nonexistent/bunny.obj";
    rc = render_run(s, &o, &rr);
    render_result_free(&rr);
    CHECK(rc == 2 && strstr(rr.err, "/nonexistent/bunny.obj"), "missing file: rc %d '%s'", rc, rr.err);

    /* sizes: zero, too small for the grid, larger than the device's memory */
    CHECK(render_check_size(s, "--size", 0, 100, 0, err, sizeof err) == 2 &&
              strstr(err, "[16, 16384]"),
          "0x100 must be refused with the range: '%s'", err);
    CHECK(render_check_size(s, "--size", 64, 20, 3, err, sizeof err) == 2 &&
              strstr(err, "8 pixel rows per model"),
          "64x20 with 3 sphere rows must be refused: '%s'", err);
    /* The device's limits, whatever this machine's are: a copy of the session whose largest
     * buffer is exactly the G-buffer of 1024x1024 (W*H*28 bytes, the documented size, for a pixel
     * count that is a multiple of the planes' 1024-pixel alignment: 29,360,128 bytes = 28 MiB)
     * and whose global memory is ample, so only the buffer rule decides. */
    {
        struct cl_session small = *s;
        small.global_mem = (cl_ulong)1 << 40;
        small.max_alloc = (cl_ulong)1024 * 1024 * 28;
        err[0] = '\0';
        CHECK(render_check_size(&small, "--size", 1024, 1024, 0, err, sizeof err) == 0,
              "1024x1024 whose G-buffer is exactly the largest buffer must be accepted: '%s'", err);
        err[0] = '\0';
        CHECK(render_check_size(&small, "--size", 1024, 1025, 0, err, sizeof err) == 2 &&
                  strstr(err, "(28 MiB)"),
              "1024x1025 (29,388,800 bytes of G-buffer > 28 MiB) must be refused naming the "
              "largest buffer, 28 MiB: '%s'", err);
        /* and the global-memory rule alone: 1 MiB of global memory holds no 1000x1000 image */
        small.max_alloc = (cl_ulong)1 << 40;
        small.global_mem = (cl_ulong)1 << 20;
        err[0] = '\0';
        CHECK(render_check_size(&small, "--size", 1024, 1024, 0, err, sizeof err) == 2 &&
                  strstr(err, "(0 MiB)"),
              "1024x1024 within half of 1 MiB of global memory must be refused: '%s'", err);
    }
    CHECK(render_check_size(s, "--size", 1920, 1080, 14, err, sizeof err) == 0,
          "1920x1080 refused: %s", err);
}

int main(void)
{
    /* a writable kernel cache of this test's own */
    char cache[600];
    const char *base = getenv("POCL_CACHE_DIR");
    snprintf(cache, sizeof cache, "%s/test_render", base ? base : "/tmp/brdfbench-pocl-cache");
    mkdir(base ? base : "/tmp/brdfbench-pocl-cache", 0777);
    mkdir(cache, 0777);
    setenv("POCL_CACHE_DIR", cache, 1);
    struct cl_session s;
    char err[512];
    int rc = clsession_open(&s, -1, -1, err, sizeof err);
    if (rc) {
        printf("no OpenCL device: %s\n0 passed, 0 failed\n", err);
        return rc == 77 ? 77 : 1;
    }
    /* made after the device check, so that a skipped run leaves nothing behind */
    if (test_tmpdir_make(tmpdir, sizeof tmpdir, "test_render") != 0)
        return 3;
    test_sphere_pixels(&s);
    test_render_run(&s);
    clsession_close(&s);
    test_tmpdir_done(tmpdir);
    return check_summary();
}
