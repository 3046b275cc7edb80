/* test_merl.c - the MERL reader (host/core/merl.c): the index mapping against values worked by
 * hand at the boundaries the format defines, the half/difference conversion against directions
 * whose angles are known, a file written by the test itself (tests/merl_synth.h) read back cell
 * by cell, a block of negative cells counted, every malformed file refused with exit 2 and its
 * own message, and the device lookup (kernels/merl.cl) against the host's. */
#include "check.h"
#include "exitcodes.h"
#include "lcg.h"
#include "merl.h"
#include "merl_synth.h"
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static char dir[512];

static void index_of(double th, double td, double pd, int want_i, int want_j, int want_k, const char *what)
{
    int i, j, k;
    long idx = merl_index(th, td, pd, &i, &j, &k);
    CHECK(i == want_i && j == want_j && k == want_k && idx == want_k + 180L * (want_j + 90L * want_i),
          "%s: (%.17g, %.17g, %.17g) -> (%d, %d, %d) index %ld, expected (%d, %d, %d)", what, th, td, pd, i, j, k, idx,
          want_i, want_j, want_k);
}

/* Hand-worked: theta_h_i = floor(90 sqrt(theta_h / (pi/2))) is i exactly at theta_h =
 * (i/90)^2 pi/2, so cell 1 starts at pi/2/8100 = 1.939e-4 and cell 45 at pi/8 (sqrt(1/4) = 1/2;
 * the divisions by 2 and 4 are exact in binary); theta_d_i reaches 45 at pi/4 and 90 (clamped
 * to 89) at pi/2; phi_d = pi gives 180, clamped to 179; phi_d < 0 is folded by + pi. */
static void test_index_mapping(void)
{
    const double up = 1 + 1e-12, down = 1 - 1e-12;
    index_of(0, 0, 0, 0, 0, 0, "theta_h = 0");
    index_of(M_PI / 2 / 8100 * up, 0, 0, 1, 0, 0, "just past the first sqrt boundary");
    index_of(M_PI / 2 / 8100 * down, 0, 0, 0, 0, 0, "just before the first sqrt boundary");
    index_of(M_PI / 8, 0, 0, 45, 0, 0, "theta_h = pi/8, the boundary of cell 45");
    index_of(M_PI / 8 * down, 0, 0, 44, 0, 0, "just before pi/8");
    index_of(M_PI / 2 * (89.0 / 90) * (89.0 / 90) * up, 0, 0, 89, 0, 0, "the last theta_h cell");
    index_of(M_PI / 2 * (89.0 / 90) * (89.0 / 90) * down, 0, 0, 88, 0, 0, "before the last theta_h cell");
    index_of(M_PI / 2, 0, 0, 89, 0, 0, "theta_h = pi/2 (90, clamped)");
    index_of(0, M_PI / 4, 0, 0, 45, 0, "theta_d = pi/4");
    index_of(0, M_PI / 4 * down, 0, 0, 44, 0, "just before theta_d = pi/4");
    index_of(0, M_PI / 2, 0, 0, 89, 0, "theta_d = pi/2 (90, clamped)");
    index_of(0, 0, M_PI, 0, 0, 179, "phi_d = pi (180, clamped)");
    index_of(0, 0, M_PI / 2, 0, 0, 90, "phi_d = pi/2");
    index_of(0, 0, -M_PI / 2, 0, 0, 90, "phi_d = -pi/2 folded to pi/2");
    index_of(0, 0, -1e-9, 0, 0, 179, "phi_d just below 0 folded to just below pi");
    index_of(0, 0, -M_PI, 0, 0, 0, "phi_d = -pi folded to 0");
    index_of(0, 0, M_PI / 180 * down, 0, 0, 0, "just before the second phi_d cell");
    index_of(0, 0, M_PI / 180 * up, 0, 0, 1, "just past the second phi_d cell");
    index_of(NAN, 0, 0, 0, 0, 0, "a NaN angle reads as 0");
    index_of(M_PI / 8, M_PI / 4, M_PI / 2, 45, 45, 90, "all three: 90 + 180 (45 + 90 * 45)");
    /* every cell's centre maps back to its cell */
    long wrong = 0;
    for (int i = 0; i < 90; ++i)
        for (int j = 0; j < 90; ++j)
            for (int k = 0; k < 180; ++k) {
                double th, td, pd;
                merl_cell_centre(i, j, k, &th, &td, &pd);
                if (merl_index(th, td, pd, NULL, NULL, NULL) != k + 180L * (j + 90L * i))
                    ++wrong;
            }
    CHECK(wrong == 0, "%ld cell centres map to another cell", wrong);
}

static void angles_of(const double L[3], const double V[3], const double N[3], double th, double td, double pd,
                      const char *what)
{
    double a, b, c;
    merl_half_diff(L, V, N, &a, &b, &c);
    CHECK(fabs(a - th) < 1e-12 && fabs(b - td) < 1e-12 && fabs(c - pd) < 1e-12,
          "%s: (%.17g, %.17g, %.17g), expected (%.17g, %.17g, %.17g)", what, a, b, c, th, td, pd);
}

/* Directions whose angles are known: L = V = N is (0, 0, .); a mirror pair in the xz plane has
 * H = N, theta_d = its polar angle and phi_d = 0 (L toward +x) or pi (L toward -x); in the yz
 * plane phi_d = pi/2; V = N with L at 0.5 rad gives H at 0.25 rad and D at 0.25 rad, phi_d = 0. */
static void test_half_diff(void)
{
    const double z[3] = { 0, 0, 1 };
    const double a = 0.3;
    double L[3] = { sin(a), 0, cos(a) }, V[3] = { -sin(a), 0, cos(a) };
    angles_of(z, z, z, 0, 0, 0, "L = V = N");
    angles_of(L, V, z, 0, a, 0, "mirror pair in xz, L toward +x");
    angles_of(V, L, z, 0, a, M_PI, "mirror pair in xz, L toward -x");
    double Ly[3] = { 0, sin(a), cos(a) }, Vy[3] = { 0, -sin(a), cos(a) };
    angles_of(Ly, Vy, z, 0, a, M_PI / 2, "mirror pair in yz");
    double L5[3] = { sin(0.5), 0, cos(0.5) };
    angles_of(L5, z, z, 0.25, 0.25, 0, "V = N, L at 0.5 rad");
    /* the same pair about a tilted normal: rotate all three by 0.7 rad about x */
    double c = cos(0.7), s = sin(0.7);
    double Lr[3] = { L5[0], c * L5[1] - s * L5[2], s * L5[1] + c * L5[2] };
    double Vr[3] = { 0, -s, c }, Nr[3] = { 0, -s, c };
    angles_of(Lr, Vr, Nr, 0.25, 0.25, 0, "V = N, L at 0.5 rad, about a tilted N");
    /* merl_dirs inverts the conversion */
    uint64_t st = 22;
    double worst = 0;
    for (int t = 0; t < 1000; ++t) {
        double th = lcg_unit(&st) * M_PI / 2, td = lcg_unit(&st) * M_PI / 2, pd = (lcg_unit(&st) * 2 - 1) * M_PI * 0.999;
        double l[3], v[3], a1, b1, c1;
        merl_dirs(th, td, pd, l, v);
        merl_half_diff(l, v, z, &a1, &b1, &c1);
        double e = fmax(fabs(a1 - th), fmax(fabs(b1 - td), fabs(c1 - pd)));
        worst = fmax(worst, e);
    }
    CHECK(worst < 1e-9, "merl_dirs then merl_half_diff: worst angle error %g", worst);
}

static void path_of(char *out, size_t len, const char *name) { snprintf(out, len, "%s/%s", dir, name); }

/* A file of distinct values read back: the lookup at each cell centre returns the value written
 * times its channel's scale (the same two doubles multiplied: exact). */
static struct merl_material pattern;
static int pattern_ok;
static void test_read_pattern(void)
{
    char p[600];
    path_of(p, sizeof p, "pattern.binary");
    struct syn_material m = { .kind = SYN_PATTERN };
    struct syn_defects d;
    syn_defects_none(&d);
    d.neg_th_lo = 10;
    d.neg_th_hi = 12;   /* 2 x 90 x 180 = 32400 green cells */
    if (syn_write(p, &m, &d) != 0) {
        CHECK(0, "cannot write %s", p);
        return;
    }
    char err[4600];
    int rc = merl_read(p, &pattern, err, sizeof err);
    CHECK(rc == 0, "read %s: %s", p, err);
    if (rc)
        return;
    pattern_ok = 1;
    CHECK(strcmp(pattern.name, "pattern") == 0, "name '%s'", pattern.name);
    CHECK(pattern.negative[0] == 0 && pattern.negative[1] == 32400 && pattern.negative[2] == 0,
          "negative cells per channel %ld %ld %ld, expected 0 32400 0", pattern.negative[0], pattern.negative[1],
          pattern.negative[2]);
    CHECK(pattern.unmeasured == 32400, "unmeasured cells %ld, expected 32400", pattern.unmeasured);
    const double z[3] = { 0, 0, 1 };
    long wrong = 0, wrong_measured = 0;
    for (int i = 0; i < 90; ++i)
        for (int j = 0; j < 90; ++j)
            for (int k = 0; k < 180; ++k) {
                long idx = k + 180L * (j + 90L * i);
                double th, td, pd, L[3], V[3], rgb[3];
                merl_cell_centre(i, j, k, &th, &td, &pd);
                merl_dirs(th, td, pd, L, V);
                int measured = merl_lookup(&pattern, L, V, z, rgb);
                int negative_block = i >= 10 && i < 12;
                if (measured == negative_block)
                    ++wrong_measured;
                for (int c = 0; c < 3; ++c) {
                    double want = (c == 1 && negative_block ? -1.0 : syn_stored(&m, c, idx)) * syn_scale[c];
                    if (rgb[c] != want)
                        ++wrong;
                }
            }
    CHECK(wrong == 0, "%ld cell values differ from the written ones", wrong);
    CHECK(wrong_measured == 0, "%ld cells with the wrong measured flag", wrong_measured);

    /* A scene's normal is anything but z: the same pairs turned with their normal by one
     * rotation (Rodrigues, 0.7 rad about (1, 2, 3)/sqrt(14)) read the same cells, since the
     * angles about N do not change (every 7th cell away from the cell edges the turn's rounding
     * could cross: centres are half a cell from them). */
    double ax[3] = { 1 / sqrt(14.0), 2 / sqrt(14.0), 3 / sqrt(14.0) }, ang = 0.7, R[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            double cross = r == c ? 0 : ((r + 1) % 3 == c ? -ax[3 - r - c] : ax[3 - r - c]);
            R[r][c] = (r == c ? cos(ang) : 0) + (1 - cos(ang)) * ax[r] * ax[c] + sin(ang) * cross;
        }
    long turned_wrong = 0, turned = 0;
    for (long idx = 0; idx < 1458000L; idx += 7) {
        int i = (int)(idx / (90 * 180)), j = (int)(idx / 180 % 90), k = (int)(idx % 180);
        if (i >= 10 && i < 12)
            continue;
        double th, td, pd, L[3], V[3], rL[3], rV[3], rN[3], rgb[3];
        merl_cell_centre(i, j, k, &th, &td, &pd);
        merl_dirs(th, td, pd, L, V);
        for (int r = 0; r < 3; ++r) {
            rL[r] = R[r][0] * L[0] + R[r][1] * L[1] + R[r][2] * L[2];
            rV[r] = R[r][0] * V[0] + R[r][1] * V[1] + R[r][2] * V[2];
            rN[r] = R[r][2];
        }
        merl_lookup(&pattern, rL, rV, rN, rgb);
        ++turned;
        for (int c = 0; c < 3; ++c)
            turned_wrong += rgb[c] != syn_stored(&m, c, idx) * syn_scale[c];
    }
    CHECK(turned > 200000 && turned_wrong == 0, "turned normal: %ld of %ld values differ", turned_wrong, turned);
}

static void refused(const char *name, const struct syn_defects *d, const char *needle1, const char *needle2)
{
    char p[600], err[4600];
    path_of(p, sizeof p, name);
    struct syn_material m = { .kind = SYN_PATTERN };
    if (syn_write(p, &m, d) != 0) {
        CHECK(0, "cannot write %s", p);
        return;
    }
    struct merl_material r;
    err[0] = '\0';
    int rc = merl_read(p, &r, err, sizeof err);
    CHECK(rc == EXIT_USAGE, "%s: exit %d, expected 2 (%s)", name, rc, err);
    CHECK(r.value == NULL, "%s: a table kept after a refusal", name);
    CHECK(strncmp(err, p, strlen(p)) == 0 && strstr(err, needle1) && (!needle2 || strstr(err, needle2)) &&
              !strchr(err, '\n'),
          "%s: message '%s' lacks the path, '%s' or '%s'", name, err, needle1, needle2 ? needle2 : "");
    remove(p);
}

static void test_malformed(void)
{
    struct syn_defects d;
    syn_defects_none(&d);
    d.trim = 1;
    refused("short1.binary", &d, "size 34992011 bytes, 1 short of the 34992012", NULL);
    syn_defects_none(&d);
    d.trim = -1;
    refused("long1.binary", &d, "size 34992013 bytes, 1 more than", NULL);
    syn_defects_none(&d);
    d.dims[0] = 90, d.dims[1] = 90, d.dims[2] = 360;
    refused("dims360.binary", &d, "dimensions 90 90 360 (expected 90 90 180", NULL);
    syn_defects_none(&d);
    d.nan_cell = 5 + 180 * (3 + 90 * 2);
    refused("nan.binary", &d, "the blue block's cell 32945 (theta_h 2, theta_d 3, phi_d 5) is NaN", NULL);
    syn_defects_none(&d);
    d.inf_cell = 7;
    refused("inf.binary", &d, "the red block's cell 7 ", "is +Inf");
    syn_defects_none(&d);
    d.all_negative = 1;
    refused("negative.binary", &d, "every cell is negative", NULL);
    syn_defects_none(&d);
    d.trim = 34992012 - 8;   /* 12 + 3 x 1458000 x 8 = 34992012 bytes */
    refused("tiny.binary", &d, "short file: 8 bytes", NULL);

    char p[600], err[4600];
    struct merl_material r;
    path_of(p, sizeof p, "absent.binary");
    CHECK(merl_read(p, &r, err, sizeof err) == EXIT_USAGE && strstr(err, "cannot open"), "absent file: %s", err);
    CHECK(merl_read(dir, &r, err, sizeof err) == EXIT_USAGE && strstr(err, "is a folder"), "a folder: %s", err);
}

/* The device lookup against the host's at random directions: the same cell (the float and the
 * double angles may straddle a boundary: then an adjacent cell), and that cell's float value. */
static void test_device(int *device_rc)
{
    struct cl_session s;
    int rc = test_session_open(&s);
    *device_rc = rc;
    if (rc != 0 || !pattern_ok)
        return;
    enum { COUNT = 40000 };
    float *L = malloc(3 * COUNT * sizeof(float)), *V = malloc(3 * COUNT * sizeof(float));
    float *rgb = malloc(3 * COUNT * sizeof(float));
    int *cell = malloc(COUNT * sizeof(int));
    uint64_t st = 2003;
    for (int t = 0; t < COUNT; ++t) {
        /* directions on the upper hemisphere; every tenth pair a mirror-near one (small theta_h) */
        double th = acos(lcg_unit(&st)), ph = 2 * M_PI * lcg_unit(&st);
        double tv = acos(lcg_unit(&st)), pv = 2 * M_PI * lcg_unit(&st);
        if (t % 10 == 0) {
            tv = th + 1e-3 * lcg_unit(&st);
            pv = ph + M_PI + 1e-3 * lcg_unit(&st);
        }
        float l[3] = { (float)(sin(th) * cos(ph)), (float)(sin(th) * sin(ph)), (float)cos(th) };
        float v[3] = { (float)(sin(tv) * cos(pv)), (float)(sin(tv) * sin(pv)), (float)cos(tv) };
        memcpy(L + 3 * t, l, sizeof l);
        memcpy(V + 3 * t, v, sizeof v);
    }
    rc = merl_eval_device(&s, &pattern, L, V, COUNT, rgb, cell);
    CHECK(rc == 0, "device lookup ran (rc %d)", rc);
    long same = 0, adjacent = 0, far = 0, value_wrong = 0;
    const double z[3] = { 0, 0, 1 };
    for (int t = 0; rc == 0 && t < COUNT; ++t) {
        double l[3] = { L[3 * t], L[3 * t + 1], L[3 * t + 2] }, v[3] = { V[3 * t], V[3 * t + 1], V[3 * t + 2] };
        double th, td, pd;
        merl_half_diff(l, v, z, &th, &td, &pd);
        int i, j, k;
        long host = merl_index(th, td, pd, &i, &j, &k);
        long dev = cell[t];
        int di = (int)(dev / 16200), dj = (int)(dev / 180 % 90), dk = (int)(dev % 180);
        if (dev == host)
            ++same;
        else if (abs(di - i) <= 1 && abs(dj - j) <= 1 && (abs(dk - k) <= 1 || abs(dk - k) == 179))
            ++adjacent;
        else
            ++far;
        for (int c = 0; c < 3 && dev >= 0 && dev < MERL_CELLS; ++c)
            if (rgb[3 * t + c] != (float)pattern.value[(size_t)c * MERL_CELLS + (size_t)dev])
                ++value_wrong;
    }
    CHECK(far == 0, "%ld device cells not adjacent to the host's", far);
    CHECK(adjacent <= COUNT / 1000, "%ld of %d device cells differ from the host's (adjacent)", adjacent, COUNT);
    CHECK(same >= COUNT - COUNT / 1000, "%ld of %d device cells equal the host's", same, COUNT);
    CHECK(value_wrong == 0, "%ld device values differ from the float table at their cell", value_wrong);
    printf("device lookup: %ld of %d cells as the host's, %ld adjacent\n", same, COUNT, adjacent);
    free(L);
    free(V);
    free(rgb);
    free(cell);
    clsession_close(&s);
}

int main(void)
{
    if (test_tmpdir_make(dir, sizeof dir, "test_merl") != 0)
        return 3;
    test_index_mapping();
    test_half_diff();
    test_read_pattern();
    test_malformed();
    int device_rc = 0;
    test_device(&device_rc);
    merl_free(&pattern);
    test_tmpdir_done(dir);
    return test_summary(device_rc);
}
