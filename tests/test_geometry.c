/* test_geometry.c - the OBJ and POV-Ray patch readers, the tessellator, smooth normals and
 * the rasteriser, on small inputs written by the test itself. Every expected value is
 * derived by hand in the comment beside it. */
#include "check.h"
#include "geometry.h"
#include "raster.h"
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char tmpdir[256];

/* The larger of a running worst error and a new one, where a NaN stays the worst (fmax drops
   a NaN, so a NaN normal or position would pass every "worst < tol" check). */
static double worse(double worst, double d)
{
    return isnan(worst) || isnan(d) ? NAN : fmax(worst, d);
}

static const char *write_tmp(const char *name, const char *text)
{
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", tmpdir, name);
    test_write_file(path, text);
    return path;
}

/* A unit cube [-1,1]^3 with six quads wound counter-clockwise seen from outside. */
static const char *cube_obj =
    "# cube\n"
    "o cube\n"
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
    "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "vt 0 0\nvn 0 0 1\n"
    "f 5 6 7 8\n"            /* +z */
    "f 1 4 3 2\n"            /* -z */
    "f 2/1 3/1 7/1 6/1\n"    /* +x, v/vt form */
    "f 1//1 5//1 8//1 4//1\n" /* -x, v//vn form */
    "f 4/1/1 8/1/1 7/1/1 3/1/1\n" /* +y, v/vt/vn form */
    "f -8 -7 -3 -4\n";       /* -y with relative indices: 1 2 6 5 */

static void test_obj_cube(void)
{
    struct mesh m;
    char err[512] = "";
    int rc = obj_read(write_tmp("cube.obj", cube_obj), &m, err, sizeof err);
    CHECK(rc == 0, "cube.obj read: rc %d: %s", rc, err);
    if (rc)
        return;
    /* 8 vertices; 6 quads fanned into 2 triangles each */
    CHECK(m.nverts == 8, "cube vertices %zu, expected 8", m.nverts);
    CHECK(m.ntris == 12, "cube triangles %zu, expected 12", m.ntris);
    /* the relative face -8 -7 -3 -4 is 1 2 6 5 (0-based 0 1 5 4): first fan triangle */
    CHECK(m.tri[30] == 0 && m.tri[31] == 1 && m.tri[32] == 5,
          "relative indices resolved to %u %u %u, expected 0 1 5", m.tri[30], m.tri[31],
          m.tri[32]);
    rc = mesh_smooth_normals(&m, err, sizeof err);
    CHECK(rc == 0, "smooth normals rc %d", rc);
    /* Angle weighting: every corner touches three faces, each with 90 degrees of corner
       angle in total however the quad was split, so the normal is the normalised sum of
       the three axis normals: sign(p) / sqrt(3) per component. */
    double worst = 0;
    for (size_t v = 0; v < m.nverts; v++)
        for (int c = 0; c < 3; c++) {
            double want = (m.pos[3 * v + c] > 0 ? 1.0 : -1.0) / sqrt(3.0);
            worst = worse(worst, fabs(m.nrm[3 * v + c] - want));
        }
    CHECK(worst < 1e-6, "cube corner normals off by %g from sign(p)/sqrt(3)", worst);
    /* Every face wound counter-clockwise from outside: (p1-p0) x (p2-p0) points away from
       the centre, i.e. along the face's centroid. */
    int outward = 0;
    for (size_t t = 0; t < m.ntris; t++) {
        const float *a = m.pos + 3 * m.tri[3 * t], *b = m.pos + 3 * m.tri[3 * t + 1],
                    *c = m.pos + 3 * m.tri[3 * t + 2];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
        double cen[3] = {a[0] + b[0] + c[0], a[1] + b[1] + c[1], a[2] + b[2] + c[2]};
        outward += n[0] * cen[0] + n[1] * cen[1] + n[2] * cen[2] > 0;
    }
    CHECK(outward == 12, "%d of 12 cube triangles wound outward", outward);
    double lo[3], hi[3];
    mesh_bounds(&m, lo, hi);
    CHECK(lo[0] == -1 && lo[1] == -1 && lo[2] == -1 && hi[0] == 1 && hi[1] == 1 && hi[2] == 1,
          "cube bounds");
    mesh_free(&m);

    /* The same cube, with each quad split along the other diagonal: the normals must not
       change (the property angle weighting has and area weighting lacks). */
    const char *alt =
        "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
        "f 6 7 8\nf 6 8 5\nf 4 3 2\nf 4 2 1\nf 3 7 6\nf 3 6 2\n"
        "f 5 8 4\nf 5 4 1\nf 8 7 3\nf 8 3 4\nf 2 6 5\nf 2 5 1\n";
    rc = obj_parse(alt, strlen(alt), "alt.obj", &m, err, sizeof err);
    CHECK(rc == 0, "alt cube parse: %s", err);
    if (rc == 0) {
        mesh_smooth_normals(&m, err, sizeof err);
        worst = 0;
        for (size_t v = 0; v < m.nverts; v++)
            for (int c = 0; c < 3; c++) {
                double want = (m.pos[3 * v + c] > 0 ? 1.0 : -1.0) / sqrt(3.0);
                worst = worse(worst, fabs(m.nrm[3 * v + c] - want));
            }
        CHECK(worst < 1e-6, "other-diagonal cube normals off by %g", worst);
        mesh_free(&m);
    }
}

/* A flat patch: control point (row i, column j) = (j/3, i/3, 0). Bernstein polynomials
   reproduce linear functions, so P(u, v) = (u, v, 0) exactly, and
   dP/du x dP/dv = (1,0,0) x (0,1,0) = (0,0,1). */
static const char *flat_patch =
    "// one flat patch\n"
    "#declare Flat = 0.01;\n"
    "bicubic_patch { type 1 flatness Flat u_steps 3 v_steps 3\n"
    "  <0, 0, 0> <0.333333333333333333, 0, 0> <0.666666666666666667, 0, 0> <1, 0, 0>\n"
    "  <0, 0.333333333333333333, 0> <0.333333333333333333, 0.333333333333333333, 0>"
    " <0.666666666666666667, 0.333333333333333333, 0> <1, 0.333333333333333333, 0>\n"
    "  <0, 0.666666666666666667, 0> <0.333333333333333333, 0.666666666666666667, 0>"
    " <0.666666666666666667, 0.666666666666666667, 0> <1, 0.666666666666666667, 0>\n"
    "  <0, 1, 0> <0.333333333333333333, 1, 0> <0.666666666666666667, 1, 0> <1, 1, 0>\n"
    "  texture { pigment { color rgb <1, 0, 0> } } /* a modifier after the points */\n"
    "}\n";

static void test_patch_flat(void)
{
    struct bezier_patch *p = NULL;
    size_t n = 0;
    char err[512] = "";
    int rc = patches_read(write_tmp("flat.inc", flat_patch), &p, &n, err, sizeof err);
    CHECK(rc == 0 && n == 1, "flat patch read: rc %d n %zu: %s", rc, n, err);
    if (rc)
        return;
    double pos[3], nrm[3];
    patch_eval(p, 0.3, 0.7, pos, nrm);
    CHECK(fabs(pos[0] - 0.3) < 1e-12 && fabs(pos[1] - 0.7) < 1e-12 && fabs(pos[2]) < 1e-12,
          "P(0.3, 0.7) = (%g %g %g), expected (0.3 0.7 0)", pos[0], pos[1], pos[2]);
    CHECK(fabs(nrm[0]) < 1e-12 && fabs(nrm[1]) < 1e-12 && fabs(nrm[2] - 1) < 1e-12,
          "N(0.3, 0.7) = (%g %g %g), expected (0 0 1)", nrm[0], nrm[1], nrm[2]);

    struct mesh m;
    rc = patches_tessellate(p, n, 4, &m, err, sizeof err);
    CHECK(rc == 0, "tessellate: %s", err);
    if (rc == 0) {
        /* density 4: 5 x 5 vertices, 4 x 4 quads of 2 triangles */
        CHECK(m.nverts == 25 && m.ntris == 32, "flat tessellation %zu vertices %zu triangles, "
              "expected 25 and 32", m.nverts, m.ntris);
        double worst = 0;
        for (size_t v = 0; v < m.nverts; v++) {
            /* vertex a * 5 + b is (u, v) = (a/4, b/4), so at (a/4, b/4, 0) */
            size_t a = v / 5, b = v % 5;
            worst = worse(worst, fabs(m.pos[3 * v + 0] - a / 4.0));
            worst = worse(worst, fabs(m.pos[3 * v + 1] - b / 4.0));
            worst = worse(worst, fabs(m.nrm[3 * v + 2] - 1.0));
        }
        CHECK(worst < 1e-6, "flat tessellation off by %g from the (u, v, 0) grid", worst);
        /* each triangle winds along the analytic +z: (b-a) x (c-a) has z = 2 * area = 1/16 */
        int good = 0;
        for (size_t t = 0; t < m.ntris; t++) {
            const float *a = m.pos + 3 * m.tri[3 * t], *b = m.pos + 3 * m.tri[3 * t + 1],
                        *c = m.pos + 3 * m.tri[3 * t + 2];
            double z = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
            good += fabs(z - 1.0 / 16.0) < 1e-6;
        }
        CHECK(good == 32, "%d of 32 triangles wound along +z with area 1/32", good);
        mesh_free(&m);
    }
    struct mesh bad;
    CHECK(patches_tessellate(p, n, 0, &bad, err, sizeof err) == 2, "density 0 must be refused");
    free(p);
}

/* A flat patch whose first row collapses to the origin (a fan): row i at radius i/3,
   column j at angle 30j degrees. dP/dv is 0 along v = 0, where the normal comes from
   the limit. Everywhere du (growing angle) x dv (growing radius) = (0, 0, -1):
   (-sin t, cos t, 0) x (cos t, sin t, 0) = (0, 0, -sin^2 t - cos^2 t). */
static void test_patch_collapsed(void)
{
    char text[2048] = "bicubic_patch {\n";
    for (int i = 0; i < 4; i++) {
        for (int j = 0; j < 4; j++) {
            double r = i / 3.0, t = j * 30.0 * 3.14159265358979323846 / 180.0;
            char pt[96];
            snprintf(pt, sizeof pt, " <%.17g, %.17g, 0>", r * cos(t), r * sin(t));
            strcat(text, pt);
        }
        strcat(text, "\n");
    }
    strcat(text, "}\n");
    struct bezier_patch *p;
    size_t n;
    char err[512] = "";
    int rc = patches_parse(text, strlen(text), "fan", &p, &n, err, sizeof err);
    CHECK(rc == 0 && n == 1, "fan patch parse: %s", err);
    if (rc)
        return;
    double pos[3], nrm[3];
    patch_eval(p, 0.5, 0.0, pos, nrm);
    CHECK(fabs(pos[0]) < 1e-15 && fabs(pos[1]) < 1e-15, "apex at (%g %g), expected origin",
          pos[0], pos[1]);
    CHECK(fabs(nrm[2] + 1.0) < 1e-9, "apex normal (%g %g %g), expected (0 0 -1)", nrm[0],
          nrm[1], nrm[2]);
    patch_eval(p, 0.25, 0.6, pos, nrm);
    CHECK(fabs(nrm[2] + 1.0) < 1e-12, "fan normal (%g %g %g), expected (0 0 -1)", nrm[0],
          nrm[1], nrm[2]);
    free(p);
}

/* A malformed file, an OBJ mesh (obj_read) or POV-Ray patches (patches_read): the read must fail
 * with 2 and a message "<path>:<line>: <problem>" that mentions words. */
enum scene_reader { OBJ_READ, PATCHES_READ };
static void expect_read_error(enum scene_reader reader, const char *name, const char *text, int line,
                              const char *words)
{
    char err[512] = "", want[600];
    const char *path = write_tmp(name, text);
    int rc;
    if (reader == OBJ_READ) {
        struct mesh m;
        rc = obj_read(path, &m, err, sizeof err);
        if (rc == 0)
            mesh_free(&m);
    } else {
        struct bezier_patch *p = NULL;
        size_t n = 0;
        rc = patches_read(path, &p, &n, err, sizeof err);
        free(p);
    }
    snprintf(want, sizeof want, "%s:%d:", path, line);
    CHECK(rc == 2, "%s: rc %d, expected 2 (%s)", name, rc, err);
    CHECK(strncmp(err, want, strlen(want)) == 0, "%s: message '%s' should start with '%s'",
          name, err, want);
    CHECK(strstr(err, words) != NULL, "%s: message '%s' should mention '%s'", name, err, words);
}

/* The first three rows of control points of a flat patch, one row a line: (j, i, 0) at row i,
 * column j. */
#define FLAT_ROWS_0_TO_2 " <0,0,0> <1,0,0> <2,0,0> <3,0,0>\n <0,1,0> <1,1,0> <2,1,0> <3,1,0>\n" \
                         " <0,2,0> <1,2,0> <2,2,0> <3,2,0>\n"

/* Malformed files, each read by its reader: the line its message must name and words it must
 * mention. */
static const struct {
    enum scene_reader reader;
    const char *name, *text;
    int line;
    const char *words;
} bad_files[] = {
    { OBJ_READ, "bad_number.obj", "v 0 0 0\nv 1 0 0\nv 0 x 0\nf 1 2 3\n", 3, "not a finite number" },
    { OBJ_READ, "short_vertex.obj", "v 0 0 0\nv 1 0\n", 2, "needs 3 to 7 numbers" },
    { OBJ_READ, "index_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n", 5, "vertex index" },
    { OBJ_READ, "zero_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4, "vertex index" },
    { OBJ_READ, "two_corners.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", 4, "at least 3 corners" },
    { OBJ_READ, "bad_normal_ref.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n", 4, "normal index" },
    { OBJ_READ, "unknown.obj", "v 0 0 0\ncurv 0 1 1 2\n", 2, "unsupported statement" },
    { OBJ_READ, "nan.obj", "v 0 nan 0\n", 1, "not a finite number" },
    { OBJ_READ, "no_faces.obj", "v 0 0 0\nv 1 0 0\n", 2, "no faces" },
    /* 15 points then '}' on line 6 */
    { PATCHES_READ, "short.inc", "bicubic_patch {\n" FLAT_ROWS_0_TO_2 " <0,3,0> <1,3,0> <2,3,0>\n}\n", 6,
      "15 control points, 16 needed" },
    { PATCHES_READ, "badnum.inc", "bicubic_patch {\n <0,0,0>\n <1, y, 0>\n}\n", 3, "expected a number" },
    { PATCHES_READ, "comma.inc", "bicubic_patch {\n <0 0 0>\n}\n", 2, "expected ','" },
    { PATCHES_READ, "open.inc", "// nothing closes this\nbicubic_patch {\n <0,0,0>\n", 2, "not closed" },
    { PATCHES_READ, "none.inc", "// no patches here\nsphere { <0,0,0>, 1 }\n", 3, "no bicubic_patch" },
    { PATCHES_READ, "xform.inc",
      "bicubic_patch {\n" FLAT_ROWS_0_TO_2 " <0,3,0> <1,3,0> <2,3,0> <3,3,0>\n translate <1, 0, 0>\n}\n", 6,
      "not supported" },
};

static void test_read_errors(void)
{
    for (size_t i = 0; i < sizeof bad_files / sizeof bad_files[0]; ++i)
        expect_read_error(bad_files[i].reader, bad_files[i].name, bad_files[i].text, bad_files[i].line,
                          bad_files[i].words);
}

/* A square [-1,1]^2 in the plane z = 0 seen from (0, 0, 5). */
static void test_raster_square(void)
{
    const char *quad = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";
    struct mesh m;
    char err[512] = "";
    int rc = obj_parse(quad, strlen(quad), "quad", &m, err, sizeof err);
    CHECK(rc == 0, "quad parse: %s", err);
    if (rc)
        return;
    mesh_smooth_normals(&m, err, sizeof err);
    struct camera cam = {{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40.0};
    struct gbuffer g;
    const int W = 101, H = 81;
    rc = gbuffer_alloc(&g, W, H, err, sizeof err);
    CHECK(rc == 0, "gbuffer alloc: %s", err);
    if (rc) {
        mesh_free(&m);
        return;
    }
    rc = raster_mesh(&g, &m, &cam, 32.0f, err, sizeof err);
    CHECK(rc == 0, "raster: %s", err);
    /* The square's half side 1 at distance 5 spans 1/5 / tan(20 deg) of the half height,
       i.e. s = (H/2) * 0.2 / tan(20 deg) pixels each way from the centre (x 50.5, y 40.5);
       pixel centres inside: |x + 0.5 - 50.5| <= s and the same in y. */
    double s = (H / 2.0) * 0.2 / tan(20.0 * 3.14159265358979323846 / 180.0);
    size_t want = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            want += fabs(x + 0.5 - W / 2.0) <= s && fabs(y + 0.5 - H / 2.0) <= s;
    CHECK(g.foreground == want, "square covers %zu pixels, expected %zu", g.foreground, want);
    /* Every covered pixel: normal (0, 0, 1), position on the ray at z = 0:
       eye + t dir with t = 5 / -dir.z. */
    double worst_p = 0, worst_n = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t i = (size_t)y * W + x;
            if (gbuffer_plane(&g, GB_SHIN)[i] == 0)
                continue;
            double dir[3];
            camera_ray(&cam, W, H, x, y, dir);
            double t = 5.0 / -dir[2];
            worst_p = worse(worst_p, fabs(gbuffer_plane(&g, GB_PX)[i] - t * dir[0]));
            worst_p = worse(worst_p, fabs(gbuffer_plane(&g, GB_PY)[i] - t * dir[1]));
            worst_p = worse(worst_p, fabs(gbuffer_plane(&g, GB_PZ)[i]));
            worst_n = worse(worst_n, fabs(gbuffer_plane(&g, GB_NZ)[i] - 1.0));
            worst_n = worse(worst_n, fabs(gbuffer_plane(&g, GB_SHIN)[i] - 32.0));
        }
    CHECK(worst_p < 1e-5, "square positions off the ray/plane intersection by %g", worst_p);
    CHECK(worst_n < 1e-6, "square normals/shininess off by %g", worst_n);
    /* Seen from behind (eye at z = -5) the square's normal flips towards the viewer. */
    struct camera back = {{0, 0, -5}, {0, 0, 0}, {0, 1, 0}, 40.0};
    memset(g.data, 0, g.stride * GB_NPLANES * sizeof(float));
    raster_mesh(&g, &m, &back, 32.0f, err, sizeof err);
    size_t centre = (size_t)(H / 2) * W + W / 2;
    CHECK(gbuffer_plane(&g, GB_NZ)[centre] == -1.0f, "back view normal z %g, expected -1",
          gbuffer_plane(&g, GB_NZ)[centre]);
    /* A nearer triangle hides the square: a small triangle at z = 1 over the centre. */
    const char *two = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n"
                      "v -0.2 -0.2 1\nv 0.2 -0.2 1\nv 0 0.2 1\nf 5 6 7\n";
    struct mesh m2;
    obj_parse(two, strlen(two), "two", &m2, err, sizeof err);
    mesh_smooth_normals(&m2, err, sizeof err);
    memset(g.data, 0, g.stride * GB_NPLANES * sizeof(float));
    raster_mesh(&g, &m2, &cam, 8.0f, err, sizeof err);
    CHECK(fabs(gbuffer_plane(&g, GB_PZ)[centre] - 1.0) < 1e-6,
          "centre pixel depth: z %g, expected the nearer triangle's 1",
          gbuffer_plane(&g, GB_PZ)[centre]);
    mesh_free(&m2);
    gbuffer_free(&g);
    mesh_free(&m);
}

/* The sphere grid: every covered pixel's position lies on its cell's sphere, and its
   normal is (P - C) / radius. */
static void test_raster_spheres(void)
{
    const int W = 200, H = 120, rows = 3, cols = 5;
    double shin[5] = {4, 16, 64, 256, 1000};
    struct gbuffer g;
    char err[256];
    struct camera cam;
    if (gbuffer_alloc(&g, W, H, err, sizeof err) != 0) {
        CHECK(0, "alloc: %s", err);
        return;
    }
    int rc = raster_spheres(&g, rows, cols, shin, &cam, err, sizeof err);
    CHECK(rc == 0, "raster_spheres: %s", err);
    struct sphere_grid sg;
    struct camera cam2;
    sphere_grid_layout(W, H, rows, cols, &sg, &cam2);
    double worst_r = 0, worst_n = 0;
    size_t count = 0, wrong_shin = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t i = (size_t)y * W + x;
            float s = gbuffer_plane(&g, GB_SHIN)[i];
            if (s == 0)
                continue;
            count++;
            int row = y * rows / H, col = x * cols / W;
            wrong_shin += s != (float)shin[col];
            double c[3], p[3] = {gbuffer_plane(&g, GB_PX)[i], gbuffer_plane(&g, GB_PY)[i],
                                 gbuffer_plane(&g, GB_PZ)[i]};
            sphere_grid_centre(&sg, row, col, c);
            double d[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
            double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            worst_r = worse(worst_r, fabs(r - sg.radius));
            worst_n = worse(worst_n, fabs(gbuffer_plane(&g, GB_NX)[i] - d[0] / sg.radius));
            worst_n = worse(worst_n, fabs(gbuffer_plane(&g, GB_NY)[i] - d[1] / sg.radius));
            worst_n = worse(worst_n, fabs(gbuffer_plane(&g, GB_NZ)[i] - d[2] / sg.radius));
        }
    CHECK(count == g.foreground && count > 0, "foreground count %zu vs %zu", count,
          g.foreground);
    CHECK(wrong_shin == 0, "%zu pixels carry another column's shininess", wrong_shin);
    CHECK(worst_r < 1e-5, "sphere positions off the sphere by %g", worst_r);
    CHECK(worst_n < 1e-5, "sphere normals off (P - C)/r by %g", worst_n);
    /* Each sphere covers about pi r^2 of its cell (cells are H/rows pixels high and the
       radius is in cell heights); perspective enlarges it slightly: 0.95..1.15 of that. */
    double px_per_unit = (double)H / rows;
    double disc = 3.14159265358979323846 * pow(sg.radius * px_per_unit, 2) * rows * cols;
    CHECK(count > 0.95 * disc && count < 1.15 * disc, "spheres cover %zu pixels, about %.0f "
          "expected", count, disc);
    gbuffer_free(&g);
}

int main(void)
{
    static void (*const tests[])(void) = { test_obj_cube, test_patch_flat, test_patch_collapsed, test_read_errors,
        test_raster_square, test_raster_spheres };
    return test_run_in_tmpdir(tmpdir, sizeof tmpdir, "test_geometry", tests, sizeof tests / sizeof tests[0]);
}
