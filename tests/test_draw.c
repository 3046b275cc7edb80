/* test_draw.c - pictures decoded back with OpenCV (through draw_read_rgb8) and checked:
 * sizes, the colour under the maximum marker, colour-bar monotonicity, a zero field drawn
 * as the colour map's bottom colour, exact pixels of RGB round trips and contact sheets,
 * and a failed write reported with the file's name. No OpenCL device needed. */
#include "check.h"
#include "draw.h"
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* matplotlib's viridis and inferno tables (_cm_listed.py), first and last entries times
 * 255, rounded: viridis (0.267004, 0.004874, 0.329415) and (0.993248, 0.906157, 0.143936);
 * inferno (0.001462, 0.000466, 0.013866) and (0.988362, 0.998364, 0.644924). */
static const int VIRIDIS_BOTTOM[3] = {68, 1, 84}, VIRIDIS_TOP[3] = {253, 231, 37};
static const int INFERNO_TOP[3] = {252, 255, 164};

static char dir[256];

static void path_in(char *out, size_t len, const char *name) { snprintf(out, len, "%s/%s", dir, name); }

static const unsigned char *px(const unsigned char *rgb, int w, int x, int y) { return rgb + ((size_t)y * w + x) * 3; }

static int near(const unsigned char *p, const int want[3], int tol)
{
    for (int k = 0; k < 3; k++)
        if (abs((int)p[k] - want[k]) > tol) return 0;
    return 1;
}

/* Index of the colour-map entry nearest to p (squared RGB distance). */
static int nearest_index(int cmap, const unsigned char *p)
{
    int best = 0;
    long bestd = -1;
    for (int i = 0; i < 256; i++) {
        unsigned char c[3];
        draw_colormap_rgb(cmap, i, c);
        long d = 0;
        for (int k = 0; k < 3; k++) d += (long)(c[k] - p[k]) * (c[k] - p[k]);
        if (bestd < 0 || d < bestd) bestd = d, best = i;
    }
    return best;
}

/* Entry index of colour map cmap is want, within tol per channel. */
static void check_entry(int cmap, int index, const int want[3], int tol, const char *what)
{
    unsigned char c[3];
    draw_colormap_rgb(cmap, index, c);
    CHECK(near(c, want, tol), "%s is %d,%d,%d", what, c[0], c[1], c[2]);
}

static void test_colormap_ends(void)
{
    check_entry(DRAW_CMAP_VIRIDIS, 0, VIRIDIS_BOTTOM, 2, "viridis bottom");
    check_entry(DRAW_CMAP_VIRIDIS, 255, VIRIDIS_TOP, 2, "viridis top");
    check_entry(DRAW_CMAP_INFERNO, 255, INFERNO_TOP, 2, "inferno top");
}

static void test_png_round_trip(void)
{
    enum { W = 7, H = 5 };
    unsigned char rgb[W * H * 3];
    for (int i = 0; i < W * H * 3; i++) rgb[i] = (unsigned char)((i * 37 + 11) & 255);
    char path[512], err[512];
    path_in(path, sizeof path, "round_trip.png");
    CHECK(draw_png_rgb8(path, W, H, rgb, err, sizeof err) == 0, "write: %s", err);
    int w = 0, h = 0;
    unsigned char *back = NULL;
    CHECK(draw_read_rgb8(path, &w, &h, &back, err, sizeof err) == 0, "read: %s", err);
    CHECK(w == W && h == H, "size %dx%d, want %dx%d", w, h, W, H);
    /* PNG is lossless: every byte comes back */
    CHECK(back && w == W && h == H && memcmp(back, rgb, sizeof rgb) == 0, "pixels differ after round trip");
    free(back);
}

static void test_heatmap(void)
{
    enum { C = 50, R = 40 };
    static float ramp[C * R], zero[C * R];
    /* v = (c / 49) (r / 39): its largest value, 1, is only at the last column of the last row */
    for (int r = 0; r < R; r++)
        for (int c = 0; c < C; c++) {
            ramp[r * C + c] = (float)((c / 49.0) * (r / 39.0));
            zero[r * C + c] = 0.0f;
        }
    struct draw_heatmap_panel p[2];
    memset(p, 0, sizeof p);
    p[0].cols = C, p[0].rows = R, p[0].values = ramp;
    p[0].x_min = 0, p[0].x_max = 1, p[0].x_label = "x / x_e(n)";
    p[0].y_min = 2, p[0].y_max = 1000, p[0].y_log = 1, p[0].y_label = "n";
    p[0].cmap = DRAW_CMAP_VIRIDIS, p[0].value_format = DRAW_FMT_PERCENT;
    p[0].bar_label = "relative error \xce\xb4", p[0].subtitle = "ramp", p[0].mark_max = 1;
    p[1] = p[0];
    p[1].values = zero, p[1].subtitle = "reference vs reference";
    char path[512], err[512];
    path_in(path, sizeof path, "heatmap.png");
    struct draw_panel_layout L[2];
    memset(L, 0, sizeof L);
    CHECK(draw_heatmap_figure(path, "test heatmap\nsecond line", 2, p, L, err, sizeof err) == 0, "heatmap: %s", err);
    int w = 0, h = 0;
    unsigned char *img = NULL;
    CHECK(draw_read_rgb8(path, &w, &h, &img, err, sizeof err) == 0, "read: %s", err);
    if (!img) return;
    CHECK(w == L[0].image_w && h == L[0].image_h, "decoded %dx%d, layout says %dx%d", w, h, L[0].image_w, L[0].image_h);
    for (int k = 0; k < 2; k++)
        CHECK(L[k].plot_x >= 0 && L[k].plot_y >= 0 && L[k].plot_x + L[k].plot_w <= w &&
                  L[k].plot_y + L[k].plot_h <= h && L[k].bar_x + L[k].bar_w <= w && L[k].bar_y + L[k].bar_h <= h,
              "panel %d does not fit in the picture", k);
    /* the maximum is the last cell (worked above), its colour the map's top */
    CHECK(L[0].max_col == C - 1 && L[0].max_row == R - 1, "max cell %d,%d", L[0].max_col, L[0].max_row);
    CHECK(fabs(L[0].max_value - 1.0) < 1e-6, "max value %g", L[0].max_value);
    CHECK(L[0].max_px >= L[0].plot_x && L[0].max_px < L[0].plot_x + L[0].plot_w &&
              L[0].max_py >= L[0].plot_y && L[0].max_py < L[0].plot_y + L[0].plot_h,
          "marker %d,%d outside the plot", L[0].max_px, L[0].max_py);
    if (L[0].max_px >= 0) {
        const unsigned char *m = px(img, w, L[0].max_px, L[0].max_py);
        CHECK(near(m, VIRIDIS_TOP, 3), "colour under the marker %d,%d,%d, want viridis top", m[0], m[1], m[2]);
    }
    /* the cell of the smallest value (0, at row 0 / column 0) sits bottom-left: bottom colour */
    {
        const unsigned char *m = px(img, w, L[0].plot_x, L[0].plot_y + L[0].plot_h - 1);
        CHECK(near(m, VIRIDIS_BOTTOM, 3), "bottom-left colour %d,%d,%d", m[0], m[1], m[2]);
    }
    /* colour bar: from bottom to top the colour-map index never falls, and the luma
     * (a lightness proxy; viridis is monotone in lightness) rises overall */
    {
        int x = L[0].bar_x + L[0].bar_w / 2, prev = -1, mono = 1;
        double luma_first = 0, luma_last = 0, luma_prev = -1;
        int luma_mono = 1;
        for (int y = L[0].bar_y + L[0].bar_h - 1; y >= L[0].bar_y; y--) {
            const unsigned char *q = px(img, w, x, y);
            int idx = nearest_index(DRAW_CMAP_VIRIDIS, q);
            if (idx < prev) mono = 0;
            prev = idx;
            double luma = 0.2126 * q[0] + 0.7152 * q[1] + 0.0722 * q[2];
            if (y == L[0].bar_y + L[0].bar_h - 1) luma_first = luma;
            luma_last = luma;
            /* 1.0: the 8-bit table itself wobbles by up to 0.25 */
            if (luma_prev >= 0 && luma < luma_prev - 1.0) luma_mono = 0;
            luma_prev = luma;
        }
        CHECK(mono, "colour bar index is not monotone");
        CHECK(luma_mono && luma_last > luma_first + 100, "colour bar lightness not rising (%g -> %g)", luma_first, luma_last);
        CHECK(near(px(img, w, x, L[0].bar_y + L[0].bar_h - 1), VIRIDIS_BOTTOM, 3), "colour bar bottom");
        CHECK(near(px(img, w, x, L[0].bar_y), VIRIDIS_TOP, 3), "colour bar top");
    }
    /* a zero field (a model against itself) is uniformly the bottom colour, unmarked */
    {
        long off = 0;
        for (int y = L[1].plot_y; y < L[1].plot_y + L[1].plot_h; y++)
            for (int x = L[1].plot_x; x < L[1].plot_x + L[1].plot_w; x++)
                if (!near(px(img, w, x, y), VIRIDIS_BOTTOM, 0)) off++;
        CHECK(off == 0, "%ld pixels of the zero field are not the bottom colour", off);
        CHECK(L[1].max_px == -1, "zero field marked at %d,%d", L[1].max_px, L[1].max_py);
    }
    free(img);
}

/* More cells than pixels: the single peak must still show (max pooling) and be marked. */
static void test_heatmap_dense_peak(void)
{
    enum { C = 2000, R = 900 };
    float *v = calloc((size_t)C * R, sizeof *v);
    if (!v) {
        CHECK(0, "cannot allocate the dense field");
        return;
    }
    v[(size_t)517 * C + 1234] = 0.5f; /* one isolated peak */
    for (int c = 0; c < 10; c++) v[c] = NAN; /* some no-data cells */
    struct draw_heatmap_panel p;
    memset(&p, 0, sizeof p);
    p.cols = C, p.rows = R, p.values = v, p.x_min = 0, p.x_max = 1, p.y_min = 0, p.y_max = 1;
    p.cmap = DRAW_CMAP_VIRIDIS, p.mark_max = 1, p.subtitle = "dense";
    char path[512], err[512];
    path_in(path, sizeof path, "dense.png");
    struct draw_panel_layout L;
    CHECK(draw_heatmap_figure(path, "dense", 1, &p, &L, err, sizeof err) == 0, "dense: %s", err);
    int w, h;
    unsigned char *img = NULL;
    if (draw_read_rgb8(path, &w, &h, &img, err, sizeof err) == 0) {
        CHECK(L.max_col == 1234 && L.max_row == 517, "dense max at %d,%d", L.max_col, L.max_row);
        CHECK(L.max_px >= 0 && near(px(img, w, L.max_px, L.max_py), VIRIDIS_TOP, 3), "dense peak not drawn at its marker");
        free(img);
    } else {
        CHECK(0, "read dense.png: %s", err);
    }
    free(v);
}

static void test_error_image_and_sheet(void)
{
    enum { W = 40, H = 30 };
    static float e[W * H];
    static unsigned char red[W * H * 3], blue[W * H * 3];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            /* largest value 1 at x = 39, y = 29; column 0 is background */
            e[y * W + x] = x == 0 ? NAN : (float)(x * y) / (float)(39 * 29);
            unsigned char *r = red + (y * W + x) * 3, *b = blue + (y * W + x) * 3;
            r[0] = 255, r[1] = 0, r[2] = 0;
            b[0] = 0, b[1] = 0, b[2] = 255;
        }
    char path[512], err[512];
    path_in(path, sizeof path, "error_image.png");
    CHECK(draw_error_image(path, W, H, e, 0.0f, "error image", err, sizeof err) == 0, "error image: %s", err);
    int w, h;
    unsigned char *img = NULL;
    if (draw_read_rgb8(path, &w, &h, &img, err, sizeof err) == 0) {
        CHECK(w >= W && h >= H, "error image %dx%d smaller than its data", w, h);
        long top = 0, grey = 0;
        static const int NODATA[3] = {90, 90, 100}; /* draw.h: NaN is drawn RGB (90, 90, 100) */
        for (int i = 0; i < w * h; i++) {
            if (near(img + 3 * i, INFERNO_TOP, 0)) top++;
            if (near(img + 3 * i, NODATA, 0)) grey++;
        }
        /* the colour bar's top rows and the one maximum pixel carry the top colour */
        CHECK(top >= 1, "no pixel of the colour map's top");
        CHECK(grey == H, "%ld background pixels, want one column of %d", grey, H);
        free(img);
    } else {
        CHECK(0, "read: %s", err);
    }
    path_in(path, sizeof path, "contact_sheet.png");
    CHECK(draw_contact_sheet(path, W, H, red, blue, e, 1.0f, "sheet", err, sizeof err) == 0, "sheet: %s", err);
    img = NULL;
    if (draw_read_rgb8(path, &w, &h, &img, err, sizeof err) == 0) {
        long nred = 0, nblue = 0;
        static const int RED[3] = {255, 0, 0}, BLUE[3] = {0, 0, 255};
        for (int i = 0; i < w * h; i++) {
            if (near(img + 3 * i, RED, 0)) nred++;
            if (near(img + 3 * i, BLUE, 0)) nblue++;
        }
        /* both images are copied 1:1: exactly W*H pure red and pure blue pixels (neither
         * colour map nor the grey text contains them) */
        CHECK(nred == W * H && nblue == W * H, "red %ld blue %ld, want %d each", nred, nblue, W * H);
        free(img);
    } else {
        CHECK(0, "read contact_sheet.png: %s", err);
    }
    /* missing inputs are refused with a message */
    CHECK(draw_contact_sheet(path, W, H, NULL, blue, e, 1.0f, "x", err, sizeof err) == -1 && err[0], "NULL image accepted");
}

static void test_line_plot_and_bars(void)
{
    enum { N = 100 };
    double x[N], y[N], y2[N];
    for (int i = 0; i < N; i++) {
        x[i] = 2.0 * pow(500.0, i / (N - 1.0));
        y[i] = 0.01 + 0.001 * i;
        y2[i] = i == 50 ? NAN : 0.02;
    }
    struct draw_series s[2] = {{x, y, N, "rising", 0, 0, 0}, {x, y2, N, "flat, with a gap", DRAW_COLOUR_BLACK, 1, 1}};
    double vl[1] = {16};
    const char *vll[1] = {"n = 16"};
    struct draw_line_plot lp;
    memset(&lp, 0, sizeof lp);
    lp.title = "plot", lp.x_label = "n", lp.y_label = "max \xce\xb4", lp.x_log = 1;
    lp.y_format = DRAW_FMT_PERCENT, lp.nseries = 2, lp.series = s;
    lp.nvlines = 1, lp.vlines = vl, lp.vline_labels = vll, lp.width = 800, lp.height = 500;
    char path[512], err[512];
    path_in(path, sizeof path, "line_plot.png");
    CHECK(draw_line_plot(path, &lp, err, sizeof err) == 0, "line plot: %s", err);
    int w, h;
    unsigned char *img = NULL;
    if (draw_read_rgb8(path, &w, &h, &img, err, sizeof err) == 0) {
        CHECK(w == 800 && h == 500, "line plot %dx%d, asked 800x500", w, h);
        /* palette colour 0 is Tableau blue (31, 119, 180): the first series is drawn in it */
        static const int BLUE[3] = {31, 119, 180};
        long n = 0;
        for (int i = 0; i < w * h; i++) n += near(img + 3 * i, BLUE, 0);
        CHECK(n > 100, "only %ld pixels of the first series' colour", n);
        free(img);
    } else {
        CHECK(0, "read line_plot.png: %s", err);
    }
    const char *labels[3] = {"phong", "fvol", "schlick"};
    double v[3] = {1.0, 2.5, NAN};
    struct draw_bar_chart bc;
    memset(&bc, 0, sizeof bc);
    bc.title = "bars", bc.x_label = "G evaluations / s", bc.nbars = 3, bc.labels = labels, bc.values = v;
    bc.highlight = 0, bc.width = 700;
    path_in(path, sizeof path, "bars.png");
    CHECK(draw_bar_chart(path, &bc, err, sizeof err) == 0, "bars: %s", err);
    img = NULL;
    if (draw_read_rgb8(path, &w, &h, &img, err, sizeof err) == 0) {
        CHECK(w == 700, "bar chart width %d, asked 700", w);
        free(img);
    } else {
        CHECK(0, "read bars.png: %s", err);
    }
}

/* Lengths (in pixels) of the runs of exactly the colour want, one per picture row that holds it,
 * distinct values in increasing order; returns how many. */
static int colour_run_lengths(const unsigned char *img, int w, int h, const int want[3], int *len, int max)
{
    int n = 0;
    for (int y = 0; y < h; y++) {
        int c = 0;
        for (int x = 0; x < w; x++) c += near(px(img, w, x, y), want, 0);
        if (c == 0) continue;
        int seen = 0;
        for (int k = 0; k < n; k++) seen |= len[k] == c;
        if (!seen && n < max) len[n++] = c;
    }
    for (int i = 1; i < n; i++)   /* insertion sort */
        for (int k = i; k > 0 && len[k - 1] > len[k]; k--) {
            int t = len[k];
            len[k] = len[k - 1];
            len[k - 1] = t;
        }
    return n;
}

/* A log value axis: bars of 2, 20 and 200 on the decades 1..1000 start at 1, so their lengths are
 * in the ratio log10(2) : log10(20) : log10(200) (computed here, not read from the picture). */
static void test_log_bars(void)
{
    const char *labels[3] = {"cheap", "middle", "pow"};
    double v[3] = {2, 20, 200};
    struct draw_bar_chart bc;
    memset(&bc, 0, sizeof bc);
    bc.title = "log bars", bc.x_label = "G evaluations / s", bc.nbars = 3, bc.labels = labels, bc.values = v;
    bc.highlight = -1, bc.width = 900, bc.x_log = 1;
    char path[512], err[512];
    path_in(path, sizeof path, "log_bars.png");
    CHECK(draw_bar_chart(path, &bc, err, sizeof err) == 0, "log bars: %s", err);
    int w, h, len[8];
    unsigned char *img = NULL;
    if (draw_read_rgb8(path, &w, &h, &img, err, sizeof err) != 0) {
        CHECK(0, "read log_bars.png: %s", err);
        return;
    }
    static const int BLUE[3] = {31, 119, 180};
    int n = colour_run_lengths(img, w, h, BLUE, len, 8);
    CHECK(n == 3, "%d different bar lengths, want 3", n);
    if (n == 3) {
        double r2 = (double)len[1] / len[0], r3 = (double)len[2] / len[0];
        double want2 = log10(20.0) / log10(2.0), want3 = log10(200.0) / log10(2.0);
        CHECK(fabs(r2 - want2) < 0.05 * want2, "bar 20 / bar 2 = %.3f, log ratio %.3f", r2, want2);
        CHECK(fabs(r3 - want3) < 0.05 * want3, "bar 200 / bar 2 = %.3f, log ratio %.3f", r3, want3);
    }
    free(img);
}

/* The first pixel (in reading order of columns, then rows) of exactly colour want: its x and y. */
static int find_colour(const unsigned char *img, int w, int h, const int want[3], int *fx, int *fy)
{
    *fx = *fy = -1;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            if (near(px(img, w, x, y), want, 0)) {
                if (*fx < 0 || x < *fx) *fx = x;
                if (*fy < 0 || y < *fy) *fy = y;
            }
    return *fx >= 0;
}

/* The diverging map's ends and middle are ColorBrewer RdBu's (33, 102, 172), white and
 * (178, 24, 43), as draw.h documents; a signed error image of -x | 0 | +x (auto scale: +-x) draws
 * exactly those, and of -x/2 | 0 | +x/2 blue-ish, white and red-ish. */
static const int RDBU_BLUE[3] = {33, 102, 172}, WHITE3[3] = {255, 255, 255}, RDBU_RED[3] = {178, 24, 43};

static void test_signed_error(void)
{
    check_entry(DRAW_CMAP_DIVERGING, 0, RDBU_BLUE, 0, "diverging bottom");
    check_entry(DRAW_CMAP_DIVERGING, 128, WHITE3, 0, "diverging middle");
    check_entry(DRAW_CMAP_DIVERGING, 255, RDBU_RED, 0, "diverging top");
    enum { W = 30, H = 10 };
    static float e[W * H];
    const float x = 0.037f;
    for (int y = 0; y < H; y++)
        for (int i = 0; i < W; i++) {
            float v = i < 10 ? -x : i < 20 ? 0 : x;
            e[y * W + i] = y < 5 ? v : v / 2;
        }
    char path[512], err[512];
    path_in(path, sizeof path, "signed.png");
    CHECK(draw_signed_error_image(path, W, H, e, 0, "signed", err, sizeof err) == 0, "signed: %s", err);
    int w, h, x0, y0;
    unsigned char *img = NULL;
    if (draw_read_rgb8(path, &w, &h, &img, err, sizeof err) != 0) {
        CHECK(0, "read signed.png: %s", err);
        return;
    }
    /* the image's top left is the first pure blue pixel (the colour bar's blue row is lower) */
    if (find_colour(img, w, h, RDBU_BLUE, &x0, &y0)) {
        CHECK(near(px(img, w, x0 + 5, y0 + 2), RDBU_BLUE, 0), "-x is not blue");
        CHECK(near(px(img, w, x0 + 15, y0 + 2), WHITE3, 0), "0 is not white");
        CHECK(near(px(img, w, x0 + 25, y0 + 2), RDBU_RED, 0), "+x is not red");
        const unsigned char *b = px(img, w, x0 + 5, y0 + 7), *r = px(img, w, x0 + 25, y0 + 7);
        CHECK(b[2] > b[0] + 40 && b[2] < 255, "-x/2 is %d,%d,%d, not a lighter blue", b[0], b[1], b[2]);
        CHECK(r[0] > r[2] + 40 && r[0] < 255, "+x/2 is %d,%d,%d, not a lighter red", r[0], r[1], r[2]);
        CHECK(near(px(img, w, x0 + 15, y0 + 7), WHITE3, 0), "0 is not white in the lower half");
    } else {
        CHECK(0, "no pure blue in signed.png");
    }
    free(img);
}

/* The sphere grid's labels: the same images drawn as a plain contact sheet and as a labelled grid;
 * the grid is wider by its row labels, and has text left of the reference panel and above it. */
static void test_contact_grid(void)
{
    enum { W = 120, H = 80 };
    static unsigned char ref[W * H * 3], mod[W * H * 3];
    static float e[W * H];
    for (int i = 0; i < W * H; i++) {
        ref[3 * i + 1] = 255;   /* pure green: where the reference panel is */
        mod[3 * i + 2] = 200;
        e[i] = (float)(i % W) / W;
    }
    const char *rows[2] = {"phong", "fq2"}, *cols[2] = {"n = 8", "n = 64"};
    struct draw_grid_labels lab = {2, 2, rows, cols};
    char plain[512], grid[512], err[512];
    path_in(plain, sizeof plain, "sheet_plain.png");
    path_in(grid, sizeof grid, "sheet_grid.png");
    CHECK(draw_contact_sheet(plain, W, H, ref, mod, e, 0, "t", err, sizeof err) == 0, "sheet: %s", err);
    CHECK(draw_contact_grid(grid, W, H, ref, mod, e, 0, "t", &lab, err, sizeof err) == 0, "grid: %s", err);
    int w0, h0, w, h, x0, y0;
    unsigned char *a = NULL, *g = NULL;
    if (draw_read_rgb8(plain, &w0, &h0, &a, err, sizeof err) || draw_read_rgb8(grid, &w, &h, &g, err, sizeof err)) {
        CHECK(0, "read sheets: %s", err);
        free(a);
        return;
    }
    CHECK(w > w0, "the labelled grid is %d wide, the plain sheet %d", w, w0);
    static const int GREEN[3] = {0, 255, 0};
    if (find_colour(g, w, h, GREEN, &x0, &y0)) {
        long left_dark = 0, above_dark = 0;
        for (int y = y0; y < y0 + H; y++)
            for (int x = 0; x < x0; x++) left_dark += px(g, w, x, y)[0] < 120;
        for (int y = y0 - 16; y < y0; y++)
            for (int x = x0; x < x0 + W; x++) above_dark += px(g, w, x, y)[0] < 120;
        CHECK(left_dark > 20, "%ld dark pixels left of the reference panel: no row labels", left_dark);
        CHECK(above_dark > 20, "%ld dark pixels above the reference panel: no column labels", above_dark);
    } else {
        CHECK(0, "no reference panel in the grid");
    }
    free(a);
    free(g);
}

/* The quick-run stamp: a band under the picture, which keeps every pixel above it. */
static void test_stamp(void)
{
    const char *labels[2] = {"a", "b"};
    double v[2] = {1, 2};
    struct draw_bar_chart bc;
    memset(&bc, 0, sizeof bc);
    bc.title = "stamp", bc.x_label = "x", bc.nbars = 2, bc.labels = labels, bc.values = v, bc.highlight = -1;
    char path[512], err[512];
    path_in(path, sizeof path, "stamped.png");
    CHECK(draw_bar_chart(path, &bc, err, sizeof err) == 0, "bars: %s", err);
    int w0, h0, w, h;
    unsigned char *a = NULL, *b = NULL;
    CHECK(draw_read_rgb8(path, &w0, &h0, &a, err, sizeof err) == 0, "read: %s", err);
    CHECK(draw_stamp_png(path, "coarse grid (--quick), not for figures", err, sizeof err) == 0, "stamp: %s", err);
    CHECK(draw_stamp_png(path, "", err, sizeof err) == -1, "an empty stamp accepted");
    if (a && draw_read_rgb8(path, &w, &h, &b, err, sizeof err) == 0) {
        CHECK(w == w0 && h > h0, "stamped %dx%d from %dx%d", w, h, w0, h0);
        CHECK(memcmp(a, b, (size_t)w0 * h0 * 3) == 0, "the picture above the stamp changed");
        /* the band: amber (255, 240, 200) behind dark red text (160, 20, 20) */
        static const int AMBER[3] = {255, 240, 200};
        long amber = 0, ink = 0;
        for (int y = h0; y < h; y++)
            for (int x = 0; x < w; x++) {
                const unsigned char *p = px(b, w, x, y);
                amber += near(p, AMBER, 0);
                ink += p[0] > 120 && p[1] < 90 && p[2] < 90;
            }
        CHECK(amber > (long)w * (h - h0) / 2, "the band is not amber (%ld pixels)", amber);
        CHECK(ink > 50, "the band holds no text (%ld dark red pixels)", ink);
    } else {
        CHECK(0, "read the stamped picture: %s", err);
    }
    free(a);
    free(b);
}

/* Vertical runs of exactly colour want in the picture's column x. */
static int runs_in_column(const unsigned char *img, int w, int h, int x, const int want[3])
{
    int runs = 0, in = 0;
    for (int y = 0; y < h; y++) {
        int m = near(px(img, w, x, y), want, 0);
        runs += m && !in;
        in = m;
    }
    return runs;
}

/* The middle of the columns of the picture's last 80 that hold colour want (the marks'
 * column; the legend's marks are at the left). */
static int mark_column(const unsigned char *img, int w, int h, const int want[3])
{
    int lo = -1, hi = -1;
    for (int x = w - 80; x < w; x++)
        for (int y = 0; y < h; y++)
            if (near(px(img, w, x, y), want, 0)) {
                if (lo < 0) lo = x;
                hi = x;
                break;
            }
    return lo < 0 ? -1 : (lo + hi) / 2;
}

/* compare's chart: 64 rows in two panels, the second run's verdict cycling better, worse, same,
 * lost: 16 marks of each colour (the colours of draw.h), one per row, in the marks' column. */
static void test_verdict_chart(void)
{
    enum { ROWS = 64, S = 2 };
    static char text[ROWS][160];
    static const char *labels[ROWS];
    static double ratio[ROWS * S];
    static int verdict[ROWS * S];
    static const int kinds[4] = {DRAW_VERDICT_BETTER, DRAW_VERDICT_WORSE, DRAW_VERDICT_SAME, DRAW_VERDICT_LOST};
    for (int i = 0; i < ROWS; i++) {
        /* a device name far wider than the label column: wrapped, not clipped */
        snprintf(text[i], sizeof text[i], "pthread-haswell-AMD EPYC 7B13 64-Core Processor with a long name %d | "
                 "model%d | default | n uniform", i, i);
        labels[i] = text[i];
        ratio[i * S] = 1;
        ratio[i * S + 1] = 0.5 + i / 32.0;
        verdict[i * S] = DRAW_VERDICT_NONE;
        verdict[i * S + 1] = kinds[i % 4];
    }
    struct draw_verdict_panel p[2] = {{"throughput: rates", 40, labels, ratio, verdict},
                                      {"accuracy: errors", 24, labels + 40, ratio + 40 * S, verdict + 40 * S}};
    const char *series[S] = {"baseline run", "new run"};
    struct draw_verdict_chart c = {"verdicts", "ratio", S, series, 2, p, 0};
    char path[512], err[512];
    path_in(path, sizeof path, "verdicts.png");
    CHECK(draw_verdict_chart(path, &c, err, sizeof err) == 0, "verdict chart: %s", err);
    int w, h;
    unsigned char *img = NULL;
    if (draw_read_rgb8(path, &w, &h, &img, err, sizeof err) != 0) {
        CHECK(0, "read verdicts.png: %s", err);
        return;
    }
    CHECK(w == 1100, "the chart grew to %d pixels wide for long labels (they wrap)", w);
    static const int GREEN[3] = {0, 140, 60}, RED[3] = {200, 0, 0}, GREY[3] = {150, 150, 150}, BLACK[3] = {0, 0, 0};
    const int *want[4] = {GREEN, RED, GREY, BLACK};
    for (int k = 0; k < 4; k++) {
        unsigned char rgb[3];
        draw_verdict_rgb(kinds[k], rgb);
        CHECK(near(rgb, want[k], 0), "verdict %d's colour is %d,%d,%d", kinds[k], rgb[0], rgb[1], rgb[2]);
        int x = mark_column(img, w, h, want[k]);
        int n = x >= 0 ? runs_in_column(img, w, h, x, want[k]) : 0;
        CHECK(n == ROWS / 4, "%d marks of verdict %d in column %d, want %d", n, kinds[k], x, ROWS / 4);
    }
    free(img);
}

static void test_errors(void)
{
    unsigned char rgb[12] = {0};
    char err[512] = "";
    const char *bad = "/nonexistent-folder-of-brdfbench/x.png";
    CHECK(draw_png_rgb8(bad, 2, 2, rgb, err, sizeof err) == -1, "write into a missing folder succeeded");
    CHECK(strstr(err, bad) != NULL, "message does not name the file: %s", err);
    CHECK(draw_png_rgb8("x.png", 0, 2, rgb, err, sizeof err) == -1, "zero width accepted");
    int w, h;
    unsigned char *img = NULL;
    CHECK(draw_read_rgb8(bad, &w, &h, &img, err, sizeof err) == -1 && strstr(err, bad), "reading a missing file: %s", err);
    struct draw_heatmap_panel p;
    memset(&p, 0, sizeof p);
    CHECK(draw_heatmap_figure("x.png", "t", 1, &p, NULL, err, sizeof err) == -1, "empty panel accepted");
}

int main(void)
{
    static void (*const tests[])(void) = { test_colormap_ends, test_png_round_trip, test_heatmap,
        test_heatmap_dense_peak, test_error_image_and_sheet, test_line_plot_and_bars, test_log_bars,
        test_signed_error, test_contact_grid, test_stamp, test_verdict_chart, test_errors };
    return test_run_in_tmpdir(dir, sizeof dir, "test_draw", tests, sizeof tests / sizeof tests[0]);
}
