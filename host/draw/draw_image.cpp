/* draw_image.cpp - the image pictures of draw.h: an RGB image as PNG, false-colour error
 * images, contact sheets, heatmap figures. */
#include "draw_common.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace draw_detail;

namespace {


double finite_max(const float *v, size_t n)
{
    double m = NAN;
    for (size_t i = 0; i < n; i++)
        if (std::isfinite(v[i]) && !(v[i] <= m)) m = v[i];
    return m;
}

/* False-colour an error image into dst (BGR, width x height) on colour map cmap over [lo, hi]. */
void error_to_bgr(const float *e, int w, int h, double lo, double hi, int cmap, cv::Mat dst)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float v = e[(size_t)y * w + x];
            if (!std::isfinite(v)) {
                dst.at<cv::Vec3b>(y, x) = cv::Vec3b((uchar)NODATA[0], (uchar)NODATA[1], (uchar)NODATA[2]);
            } else {
                dst.at<cv::Vec3b>(y, x) = cmap_bgr(cmap, value_index(v, lo, hi));
            }
        }
}

double finite_abs_max(const float *v, size_t n)
{
    double m = NAN;
    for (size_t i = 0; i < n; i++)
        if (std::isfinite(v[i]) && !(std::fabs(v[i]) <= m)) m = std::fabs(v[i]);
    return m;
}

bool check_image_args(const char *path, int width, int height, const void *data, const char *what,
                      char *err, size_t errlen)
{
    if (!check_path(path, err, errlen)) return false;
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384) {
        set_err(err, errlen, "%s: image size %dx%d outside 1..16384", path, width, height);
        return false;
    }
    if (!data) {
        set_err(err, errlen, "%s: no %s data", path, what);
        return false;
    }
    return true;
}

/* What image_row draws: one error image, or a contact sheet (reference, model, error), with the
 * error's colour map and scale and, for a grid of small images, its row and column labels. */
struct RowSpec {
    int w, h;
    const unsigned char *ref, *model;   /* both NULL: the error image alone */
    const float *err;
    double lo, hi;
    int cmap;
    const char *err_caption, *bar_caption, *title;
    const draw_grid_labels *labels;     /* may be NULL */
};

/* The font scale at which every label fits a band of `band` pixels (height for rows). */
double label_scale(const char *const *labels, int n, int band, bool widths)
{
    double scale = S_TICK;
    for (; scale > 0.3; scale -= 0.02) {
        bool fits = true;
        for (int i = 0; i < n && fits; i++) {
            cv::Size sz = text_size(ascii(labels[i]), scale);
            fits = widths ? sz.width + 4 <= band : sz.height + 3 <= band;
        }
        if (fits) break;
    }
    return scale;
}

/* Row labels right-aligned at x_right, centred on their bands; column labels above each panel. */
void grid_labels(cv::Mat &img, const RowSpec &r, int x_right, const std::vector<int> &panel_x, int y0)
{
    const draw_grid_labels &g = *r.labels;
    double rs = label_scale(g.row_labels, g.rows, r.h / g.rows, false);
    for (int k = 0; k < g.rows; k++)
        put(img, ascii(g.row_labels[k]), x_right, y0 + (int)((k + 0.5) * r.h / g.rows), rs, 1, 0);
    double cs = label_scale(g.col_labels, g.cols, r.w / g.cols, true);
    for (int x0 : panel_x)
        for (int c = 0; c < g.cols; c++)
            put(img, ascii(g.col_labels[c]), x0 + (int)((c + 0.5) * r.w / g.cols), y0 - 4, cs, 0, 1);
}

int row_label_width(const RowSpec &r)
{
    if (!r.labels) return 0;
    const draw_grid_labels &g = *r.labels;
    double rs = label_scale(g.row_labels, g.rows, r.h / g.rows, false);
    int w = 0;
    for (int k = 0; k < g.rows; k++) w = std::max(w, text_size(ascii(g.row_labels[k]), rs).width);
    return w + 8;
}

/* Images of width x height in a row, captions above, the error colour bar on the right; the
 * last image is the error. */
cv::Mat image_row(const RowSpec &r)
{
    const int w = r.w, h = r.h;
    bool sheet = r.ref != nullptr;
    const int M = 12, GAP = 12, BAR_W = 20, BAR_MIN_H = 220;
    int nimg = sheet ? 3 : 1;
    std::string t = ascii(r.title);
    int th = title_height(t);
    int col_h = r.labels ? 18 : 0;
    int cap_h = (sheet ? 26 : 0) + col_h;
    int bar_h = std::max(h, BAR_MIN_H);
    int bar_extent = colour_bar_extent(r.lo, r.hi, DRAW_FMT_PLAIN, BAR_W);
    const char *captions[3] = {"reference", "model", r.err_caption};
    /* each image sits centred in a slot at least as wide as its caption */
    int slot = w;
    if (sheet)
        for (int k = 0; k < 3; k++) slot = std::max(slot, text_size(captions[k], S_LABEL).width + 8);
    int left = M + row_label_width(r);
    int width = left + nimg * slot + (nimg - 1) * GAP + 18 + bar_extent + M;
    int title_w = 0;
    for (const std::string &l : split_lines(t)) title_w = std::max(title_w, text_size(l, S_TITLE).width + 2 * M);
    width = std::max(width, title_w);
    int height = th + cap_h + bar_h + M;
    cv::Mat img(height, width, CV_8UC3, WHITE);
    put_title(img, t);
    int y0 = th + cap_h;
    std::vector<int> panel_x;
    for (int k = 0; k < nimg; k++) {
        int sx = left + k * (slot + GAP), x0 = sx + (slot - w) / 2;
        cv::Mat dst = img(cv::Rect(x0, y0, w, h));
        if (sheet && k == 0) rgb_to_bgr(r.ref, w, h, dst);
        else if (sheet && k == 1) rgb_to_bgr(r.model, w, h, dst);
        else error_to_bgr(r.err, w, h, r.lo, r.hi, r.cmap, dst);
        if (sheet) put(img, captions[k], sx + slot / 2, y0 - 6 - col_h, S_LABEL, 0, 1);
        panel_x.push_back(x0);
    }
    if (r.labels) grid_labels(img, r, panel_x[0] - 6, panel_x, y0);
    int bx = left + nimg * slot + (nimg - 1) * GAP + 18;
    draw_colour_bar(img, cv::Rect(bx, y0, BAR_W, bar_h), r.cmap, r.lo, r.hi, DRAW_FMT_PLAIN, r.bar_caption);
    return img;
}

/* The RowSpec of an absolute error (inferno over [0, vmax]). */
RowSpec abs_row(int w, int h, const unsigned char *ref, const unsigned char *model, const float *abs_err, float vmax,
                const char *title, const draw_grid_labels *labels)
{
    RowSpec r{w, h, ref, model, abs_err, 0, 1, DRAW_CMAP_INFERNO, "abs. error", "absolute error", title, labels};
    colour_scale(0, vmax, finite_max(abs_err, (size_t)w * h), &r.lo, &r.hi);
    return r;
}

/* ---- heatmaps --------------------------------------------------------------------- */

struct PanelGeom {
    int left, plot_w, plot_h, bar_gap, bar_w, bar_extent, width;
};

const int HM_PLOT_W = 460, HM_PLOT_H = 360, HM_TOP = 34, HM_BOTTOM = 64, HM_BAR_W = 22;

/* Map pixel index p (0..npix-1) to the cells it shows: [lo, hi]. When cells outnumber
 * pixels, a pixel covers several cells and shows their maximum, so a peak never vanishes. */
void pixel_cells(int p, int npix, int ncells, int *lo, int *hi)
{
    if (ncells <= npix) {
        int c = (int)((p + 0.5) * ncells / npix);
        *lo = *hi = std::min(c, ncells - 1);
    } else {
        *lo = (int)((long long)p * ncells / npix);
        *hi = std::max(*lo, (int)(((long long)(p + 1) * ncells + npix - 1) / npix) - 1);
        *hi = std::min(*hi, ncells - 1);
    }
}

/* The middle pixel of those that show cell c. */
int cell_pixel(int c, int npix, int ncells)
{
    int first = -1, last = -1;
    for (int p = 0; p < npix; p++) {
        int lo, hi;
        pixel_cells(p, npix, ncells, &lo, &hi);
        if (c >= lo && c <= hi) {
            if (first < 0) first = p;
            last = p;
        }
    }
    return first < 0 ? -1 : (first + last) / 2;
}

bool check_panel(const draw_heatmap_panel &p, const char *path, int k, char *err, size_t errlen)
{
    if (p.cols < 1 || p.rows < 1 || p.cols > 100000 || p.rows > 100000 || !p.values) {
        set_err(err, errlen, "%s: panel %d has no grid (cols %d, rows %d)", path, k, p.cols, p.rows);
        return false;
    }
    if (!(std::isfinite(p.x_min) && std::isfinite(p.x_max) && p.x_max > p.x_min) ||
        !(std::isfinite(p.y_min) && std::isfinite(p.y_max) && p.y_max > p.y_min) ||
        (p.x_log && !(p.x_min > 0)) || (p.y_log && !(p.y_min > 0))) {
        set_err(err, errlen, "%s: panel %d has an empty or invalid axis range", path, k);
        return false;
    }
    return true;
}

void draw_panel(cv::Mat &img, int x0, int y0, const draw_heatmap_panel &p, const PanelGeom &g,
                draw_panel_layout *out)
{
    size_t n = (size_t)p.cols * p.rows;
    /* the largest finite value and its cell (first one in row-major order) */
    double vmaxd = NAN;
    int mc = -1, mr = -1;
    for (size_t i = 0; i < n; i++) {
        float v = p.values[i];
        if (std::isfinite(v) && !(v <= vmaxd)) {
            vmaxd = v;
            mc = (int)(i % p.cols);
            mr = (int)(i / p.cols);
        }
    }
    double lo, hi;
    colour_scale(p.vmin, p.vmax, vmaxd, &lo, &hi);

    cv::Rect plot(x0 + g.left, y0 + HM_TOP, g.plot_w, g.plot_h);
    put(img, ascii(p.subtitle), plot.x + plot.width / 2, y0 + 8, S_LABEL, 0, -1);

    std::vector<int> clo(plot.width), chi(plot.width), rlo(plot.height), rhi(plot.height);
    for (int px = 0; px < plot.width; px++) pixel_cells(px, plot.width, p.cols, &clo[px], &chi[px]);
    for (int q = 0; q < plot.height; q++) pixel_cells(q, plot.height, p.rows, &rlo[q], &rhi[q]);
    for (int py = 0; py < plot.height; py++) {
        int q = plot.height - 1 - py; /* row 0 at the bottom */
        for (int px = 0; px < plot.width; px++) {
            double m = NAN;
            for (int r = rlo[q]; r <= rhi[q]; r++)
                for (int c = clo[px]; c <= chi[px]; c++) {
                    float v = p.values[(size_t)r * p.cols + c];
                    if (std::isfinite(v) && !(v <= m)) m = v;
                }
            cv::Vec3b col = std::isfinite(m) ? cmap_bgr(p.cmap, value_index(m, lo, hi))
                                             : cv::Vec3b((uchar)NODATA[0], (uchar)NODATA[1], (uchar)NODATA[2]);
            img.at<cv::Vec3b>(plot.y + py, plot.x + px) = col;
        }
    }
    cv::rectangle(img, cv::Rect(plot.x - 1, plot.y - 1, plot.width + 2, plot.height + 2), INK, 1);

    /* axes: the first and last cell centres are x_min/x_max, y_min/y_max */
    Axis ax{p.x_min, p.x_max, p.x_log != 0, plot.x + 0.5 * plot.width / p.cols,
            plot.x + plot.width - 0.5 * plot.width / p.cols};
    Axis ay{p.y_min, p.y_max, p.y_log != 0, plot.y + plot.height - 0.5 * plot.height / p.rows,
            plot.y + 0.5 * plot.height / p.rows};
    if (p.cols == 1) ax.p0 = plot.x, ax.p1 = plot.x + plot.width - 1;
    if (p.rows == 1) ay.p0 = plot.y + plot.height - 1, ay.p1 = plot.y;
    draw_x_ticks(img, ax, plot.y + plot.height + 1, DRAW_FMT_PLAIN, 5);
    int yw = draw_y_ticks(img, ay, plot.x - 1, DRAW_FMT_PLAIN, 6);
    put(img, ascii(p.x_label), plot.x + plot.width / 2, plot.y + plot.height + 34, S_LABEL, 0, -1);
    put_vertical(img, ascii(p.y_label), plot.x - 8 - yw - 16, plot.y + plot.height / 2, S_LABEL);

    cv::Rect bar(plot.x + plot.width + g.bar_gap, plot.y, g.bar_w, plot.height);
    draw_colour_bar(img, bar, p.cmap, lo, hi, p.value_format, ascii(p.bar_label));

    int mpx = -1, mpy = -1;
    if (p.mark_max && mc >= 0 && vmaxd > lo) {
        mpx = plot.x + cell_pixel(mc, plot.width, p.cols);
        mpy = plot.y + (plot.height - 1 - cell_pixel(mr, plot.height, p.rows));
        /* a ring that leaves the cell itself visible: white inside black, seen on any colour */
        cv::circle(img, cv::Point(mpx, mpy), 9, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
        cv::circle(img, cv::Point(mpx, mpy), 9, WHITE, 1, cv::LINE_AA);
        /* and a tick on the colour bar at the maximum */
        int by = (int)std::lround(bar.y + (bar.height - 1) * (1 - (vmaxd - lo) / (hi - lo)));
        if (by >= bar.y && by < bar.y + bar.height) {
            cv::Point tri[3] = {cv::Point(bar.x - 2, by), cv::Point(bar.x - 10, by - 5), cv::Point(bar.x - 10, by + 5)};
            cv::fillConvexPoly(img, tri, 3, INK, cv::LINE_AA);
        }
    }
    if (out) {
        out->plot_x = plot.x;
        out->plot_y = plot.y;
        out->plot_w = plot.width;
        out->plot_h = plot.height;
        out->bar_x = bar.x;
        out->bar_y = bar.y;
        out->bar_w = bar.width;
        out->bar_h = bar.height;
        out->max_col = mc;
        out->max_row = mr;
        out->max_px = mpx;
        out->max_py = mpy;
        out->max_value = vmaxd;
        out->vmin_used = lo;
        out->vmax_used = hi;
    }
}

/* The geometry of a heatmap panel whose grid is plot_w x plot_h pixels. */
PanelGeom panel_geom(const draw_heatmap_panel &p, int plot_w, int plot_h)
{
    PanelGeom g;
    double fmax = finite_max(p.values, (size_t)p.cols * p.rows), lo, hi;
    colour_scale(p.vmin, p.vmax, fmax, &lo, &hi);
    Axis ay{p.y_min, p.y_max, p.y_log != 0, 0, 1};
    g.left = 8 + 24 + y_label_width(ay, DRAW_FMT_PLAIN, 6) + 8 + 8;
    g.plot_w = plot_w;
    g.plot_h = plot_h;
    g.bar_gap = 20;
    g.bar_w = HM_BAR_W;
    g.bar_extent = colour_bar_extent(lo, hi, p.value_format, HM_BAR_W);
    g.width = g.left + g.plot_w + g.bar_gap + g.bar_extent + 16;
    return g;
}

} /* namespace */

extern "C" int draw_png_rgb8(const char *path, int width, int height, const unsigned char *rgb, char *err,
                             size_t errlen)
{
    if (!check_image_args(path, width, height, rgb, "pixel", err, errlen)) return -1;
    return draw_png(path, err, errlen, [&]() -> cv::Mat {
        cv::Mat img(height, width, CV_8UC3);
        rgb_to_bgr(rgb, width, height, img);
        return img;
    });
}

extern "C" int draw_error_image(const char *path, int width, int height, const float *abs_err, float vmax,
                                const char *title, char *err, size_t errlen)
{
    if (!check_image_args(path, width, height, abs_err, "error", err, errlen)) return -1;
    return draw_png(path, err, errlen,
                    [&]() { return image_row(abs_row(width, height, nullptr, nullptr, abs_err, vmax, title, nullptr)); });
}

extern "C" int draw_signed_error_image(const char *path, int width, int height, const float *signed_err,
                                       float vmax, const char *title, char *err, size_t errlen)
{
    if (!check_image_args(path, width, height, signed_err, "error", err, errlen)) return -1;
    double m = (std::isfinite(vmax) && vmax > 0) ? vmax : finite_abs_max(signed_err, (size_t)width * height);
    if (!(std::isfinite(m) && m > 0)) m = 1;
    RowSpec r{width, height, nullptr, nullptr, signed_err, -m, m, DRAW_CMAP_DIVERGING, "signed error",
              "model - reference", title, nullptr};
    return draw_png(path, err, errlen, [&]() { return image_row(r); });
}

static int contact(const char *path, int width, int height, const unsigned char *ref_rgb,
                   const unsigned char *model_rgb, const float *abs_err, float vmax, const char *title,
                   const draw_grid_labels *labels, char *err, size_t errlen, bool of_peak = false)
{
    if (!check_image_args(path, width, height, abs_err, "error", err, errlen)) return -1;
    if (!ref_rgb || !model_rgb) {
        set_err(err, errlen, "%s: contact sheet needs both the reference and the model image", path);
        return -1;
    }
    return draw_png(path, err, errlen,
                    [&]() {
                        RowSpec r = abs_row(width, height, ref_rgb, model_rgb, abs_err, vmax, title, labels);
                        if (of_peak) {   /* the errors are relative to each row's reference peak, not radiance */
                            r.err_caption = "error / peak";
                            r.bar_caption = "error / reference peak";
                        }
                        return image_row(r);
                    });
}

extern "C" int draw_contact_sheet(const char *path, int width, int height, const unsigned char *ref_rgb,
                                  const unsigned char *model_rgb, const float *abs_err, float vmax,
                                  const char *title, char *err, size_t errlen)
{
    return contact(path, width, height, ref_rgb, model_rgb, abs_err, vmax, title, nullptr, err, errlen);
}

extern "C" int draw_contact_grid(const char *path, int width, int height, const unsigned char *ref_rgb,
                                 const unsigned char *model_rgb, const float *abs_err, float vmax, const char *title,
                                 const struct draw_grid_labels *labels, char *err, size_t errlen)
{
    if (!labels || labels->rows < 1 || labels->cols < 1 || labels->rows > height || labels->cols > width ||
        !labels->row_labels || !labels->col_labels) {
        set_err(err, errlen, "%s: a contact grid needs 1..%d rows and 1..%d columns, each labelled", path, height, width);
        return -1;
    }
    return contact(path, width, height, ref_rgb, model_rgb, abs_err, vmax, title, labels, err, errlen, true);
}

extern "C" int draw_heatmap_figure(const char *path, const char *title, int npanels,
                                   const struct draw_heatmap_panel *panels, struct draw_panel_layout *layout,
                                   char *err, size_t errlen)
{
    if (!check_path(path, err, errlen)) return -1;
    if (npanels < 1 || npanels > 4 || !panels) {
        set_err(err, errlen, "%s: a heatmap figure has 1..4 panels, not %d", path, npanels);
        return -1;
    }
    for (int k = 0; k < npanels; k++)
        if (!check_panel(panels[k], path, k, err, errlen)) return -1;
    return draw_png(path, err, errlen, [&]() -> cv::Mat {
        std::vector<PanelGeom> geom(npanels);
        int total_w = 0;
        for (int k = 0; k < npanels; k++) {
            geom[k] = panel_geom(panels[k], HM_PLOT_W, HM_PLOT_H);
            total_w += geom[k].width;
        }
        std::string t = ascii(title);
        int panels_w = total_w;
        for (const std::string &l : split_lines(t)) total_w = std::max(total_w, text_size(l, S_TITLE).width + 24);
        int th = title_height(t);
        int height = th + HM_TOP + HM_PLOT_H + HM_BOTTOM;
        cv::Mat img(height, total_w, CV_8UC3, WHITE);
        put_title(img, t);
        int x0 = (total_w - panels_w) / 2; /* centred under a title wider than the panels */
        for (int k = 0; k < npanels; k++) {
            draw_panel(img, x0, th, panels[k], geom[k], layout ? &layout[k] : nullptr);
            if (layout) {
                layout[k].image_w = img.cols;
                layout[k].image_h = img.rows;
            }
            x0 += geom[k].width;
        }
        return img;
    });
}

extern "C" int draw_heatmap_grid(const char *path, const char *title, int npanels, int ncols,
                                 const struct draw_heatmap_panel *panels, char *err, size_t errlen)
{
    if (!check_path(path, err, errlen)) return -1;
    if (npanels < 1 || npanels > 400 || ncols < 1 || ncols > 8 || !panels) {
        set_err(err, errlen, "%s: a heatmap grid has 1..400 panels in 1..8 columns, not %d in %d", path, npanels, ncols);
        return -1;
    }
    for (int k = 0; k < npanels; k++)
        if (!check_panel(panels[k], path, k, err, errlen)) return -1;
    return draw_png(path, err, errlen, [&]() -> cv::Mat {
        const int PW = 240, PH = 170, row_h = HM_TOP + PH + HM_BOTTOM;
        std::vector<PanelGeom> geom(npanels);
        std::vector<int> col_w(ncols, 0);
        for (int k = 0; k < npanels; k++) {
            geom[k] = panel_geom(panels[k], PW, PH);
            col_w[k % ncols] = std::max(col_w[k % ncols], geom[k].width);
        }
        int total_w = 0;
        for (int w : col_w) total_w += w;
        std::string t = ascii(title);
        int panels_w = total_w;
        for (const std::string &l : split_lines(t)) total_w = std::max(total_w, text_size(l, S_TITLE).width + 24);
        int th = title_height(t), nrows = (npanels + ncols - 1) / ncols;
        cv::Mat img(th + nrows * row_h, total_w, CV_8UC3, WHITE);
        put_title(img, t);
        for (int k = 0; k < npanels; k++) {
            int x0 = (total_w - panels_w) / 2;
            for (int c = 0; c < k % ncols; c++) x0 += col_w[c];
            draw_panel(img, x0, th + (k / ncols) * row_h, panels[k], geom[k], nullptr);
        }
        return img;
    });
}

