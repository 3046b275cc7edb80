/* draw_plot.cpp - the line plots and bar charts of draw.h. */
#include "draw_common.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace draw_detail;

namespace {

/* ---- line plots --------------------------------------------------------------------- */

bool usable(double v, bool log) { return std::isfinite(v) && (!log || v > 0); }

/* Liang-Barsky: clips the segment a-b to the box [x0, x1] x [y0, y1]; false when nothing of it
 * (or a non-finite end) is inside. */
bool clip_segment(cv::Point2d &a, cv::Point2d &b, double x0, double y0, double x1, double y1)
{
    if (!std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(b.x) || !std::isfinite(b.y)) return false;
    double t0 = 0, t1 = 1, dx = b.x - a.x, dy = b.y - a.y;
    const double p[4] = {-dx, dx, -dy, dy}, q[4] = {a.x - x0, x1 - a.x, a.y - y0, y1 - a.y};
    for (int k = 0; k < 4; k++) {
        if (p[k] == 0) {
            if (q[k] < 0) return false;
            continue;
        }
        double r = q[k] / p[k];
        if (p[k] < 0) {
            if (r > t1) return false;
            if (r > t0) t0 = r;
        } else {
            if (r < t0) return false;
            if (r < t1) t1 = r;
        }
    }
    cv::Point2d na = a + (b - a) * t0, nb = a + (b - a) * t1;
    a = na;
    b = nb;
    return true;
}

/* Polyline with an optional dash pattern, clipped by drawing into the plot's sub-image. */
void draw_polyline(cv::Mat &roi, const std::vector<cv::Point2d> &pts, cv::Scalar col, bool dashed, int thick)
{
    if (pts.size() == 1) {
        if (!(std::fabs(pts[0].x) < 1e6 && std::fabs(pts[0].y) < 1e6)) return;   /* far outside */
        cv::circle(roi, cv::Point((int)std::lround(pts[0].x), (int)std::lround(pts[0].y)), 2, col, -1, cv::LINE_AA);
        return;
    }
    const double on = 9, off = 6;
    double phase = 0;
    for (size_t i = 1; i < pts.size(); i++) {
        cv::Point2d a = pts[i - 1], b = pts[i];
        /* only what lies in the picture is drawn: a point far outside (a range a hand-edited
           plots.json made 1e-15 wide) would make a segment of 1e300 pixels to dash */
        if (!clip_segment(a, b, -8.0, -8.0, roi.cols + 8.0, roi.rows + 8.0)) continue;
        if (!dashed) {
            /* sub-pixel precision: 4 fractional bits */
            cv::line(roi, cv::Point((int)std::lround(a.x * 16), (int)std::lround(a.y * 16)),
                     cv::Point((int)std::lround(b.x * 16), (int)std::lround(b.y * 16)), col, thick, cv::LINE_AA, 4);
            continue;
        }
        double len = cv::norm(b - a), pos = 0;
        while (pos < len) {
            double period_left = (phase < on) ? on - phase : on + off - phase;
            double step = std::min(period_left, len - pos);
            if (phase < on) {
                cv::Point2d s = a + (b - a) * (pos / len), e = a + (b - a) * ((pos + step) / len);
                cv::line(roi, cv::Point((int)std::lround(s.x * 16), (int)std::lround(s.y * 16)),
                         cv::Point((int)std::lround(e.x * 16), (int)std::lround(e.y * 16)), col, thick, cv::LINE_AA, 4);
            }
            pos += step;
            phase += step;
            if (phase >= on + off) phase -= on + off;
        }
    }
}

void data_range(const struct draw_line_plot *p, bool xaxis, double *lo, double *hi)
{
    bool log = xaxis ? p->x_log : p->y_log;
    *lo = INFINITY;
    *hi = -INFINITY;
    for (int s = 0; s < p->nseries; s++) {
        const draw_series &se = p->series[s];
        for (int i = 0; i < se.count; i++) {
            double x = se.x[i], y = se.y[i];
            if (!usable(x, p->x_log) || !usable(y, p->y_log)) continue;
            double v = xaxis ? x : y;
            *lo = std::min(*lo, v);
            *hi = std::max(*hi, v);
        }
    }
    if (!(*hi >= *lo)) {
        *lo = log ? 1 : 0;
        *hi = log ? 10 : 1;
    }
}

/* Axis range: the caller's, or the data's padded to tick positions. */
void finish_range(double lo, double hi, bool log, bool include_zero, bool pad, double *out_lo, double *out_hi)
{
    if (log) {
        if (hi <= lo) {
            lo /= 2;
            hi *= 2;
        }
        if (pad) {
            double f = std::pow(hi / lo, 0.04);
            lo /= f;
            hi *= f;
        }
    } else {
        if (include_zero && lo > 0) lo = 0;
        if (include_zero && hi < 0) hi = 0;
        if (hi <= lo) {
            double d = lo == 0 ? 1 : std::fabs(lo) * 0.1;
            lo -= d;
            hi += d;
        }
        if (pad) {
            double step = nice_step((hi - lo) / 6);
            double nlo = std::floor(lo / step + 1e-9) * step, nhi = std::ceil(hi / step - 1e-9) * step;
            if (nhi - hi < 0.02 * (nhi - nlo)) nhi += step * 0.5; /* room above the highest curve */
            lo = nlo;
            hi = nhi;
        }
    }
    *out_lo = lo;
    *out_hi = hi;
}

} /* namespace */

extern "C" int draw_line_plot(const char *path, const struct draw_line_plot *p, char *err, size_t errlen)
{
    if (!check_path(path, err, errlen)) return -1;
    if (!p || p->nseries < 0 || (p->nseries > 0 && !p->series)) {
        set_err(err, errlen, "%s: no plot description", path);
        return -1;
    }
    for (int s = 0; s < p->nseries; s++)
        if (p->series[s].count < 0 || (p->series[s].count > 0 && (!p->series[s].x || !p->series[s].y))) {
            set_err(err, errlen, "%s: series %d has no data", path, s);
            return -1;
        }
    if ((p->x_log && p->x_max > p->x_min && !(p->x_min > 0)) || (p->y_log && p->y_max > p->y_min && !(p->y_min > 0))) {
        set_err(err, errlen, "%s: a log axis needs a positive range", path);
        return -1;
    }
    return draw_png(path, err, errlen, [&]() -> cv::Mat {
        double xlo, xhi, ylo, yhi;
        if (p->x_max > p->x_min) {
            xlo = p->x_min;
            xhi = p->x_max;
        } else {
            data_range(p, true, &xlo, &xhi);
            finish_range(xlo, xhi, p->x_log, false, false, &xlo, &xhi);
        }
        if (p->y_max > p->y_min) {
            ylo = p->y_min;
            yhi = p->y_max;
        } else {
            data_range(p, false, &ylo, &yhi);
            finish_range(ylo, yhi, p->y_log, true, true, &ylo, &yhi);
        }
        int W = p->width > 0 ? p->width : 1000, H = p->height > 0 ? p->height : 620;
        std::string t = ascii(p->title);
        int th = title_height(t);
        /* legend to the right of the plot, never over the curves */
        int legend_w = 0, nleg = 0;
        for (int s = 0; s < p->nseries; s++)
            if (p->series[s].label) {
                legend_w = std::max(legend_w, text_size(ascii(p->series[s].label), S_LABEL).width);
                nleg++;
            }
        legend_w = nleg ? legend_w + 70 : 0;
        Axis ay{ylo, yhi, p->y_log != 0, 0, 1};
        int left = 12 + 24 + y_label_width(ay, p->y_format, 7) + 14;
        int right = 24 + legend_w;
        int bottom = 66;
        W = std::max(W, left + right + 200);
        H = std::max(H, th + bottom + 150);
        cv::Rect plot(left, th + 8, W - left - right, H - th - 8 - bottom);
        cv::Mat img(H, W, CV_8UC3, WHITE);
        put_title(img, t);
        Axis ax{xlo, xhi, p->x_log != 0, (double)plot.x, (double)(plot.x + plot.width - 1)};
        ay = Axis{ylo, yhi, p->y_log != 0, (double)(plot.y + plot.height - 1), (double)plot.y};
        draw_x_ticks(img, ax, plot.y + plot.height, DRAW_FMT_PLAIN, 8, plot.y);
        draw_y_ticks(img, ay, plot.x - 1, p->y_format, 7, plot.x + plot.width - 1);
        int yw = y_label_width(ay, p->y_format, 7);
        put(img, ascii(p->x_label), plot.x + plot.width / 2, plot.y + plot.height + 36, S_LABEL, 0, -1);
        put_vertical(img, ascii(p->y_label), plot.x - 8 - yw - 18, plot.y + plot.height / 2, S_LABEL);

        cv::Mat roi = img(plot);
        for (int v = 0; v < p->nvlines; v++) {
            double xv = p->vlines[v];
            if (!ax.inside(xv)) continue;
            int px = (int)std::lround(ax.map(xv)) - plot.x;
            for (int y = 0; y < plot.height; y += 6)
                cv::line(roi, cv::Point(px, y), cv::Point(px, std::min(y + 2, plot.height - 1)), cv::Scalar(110, 110, 110), 1);
            if (p->vline_labels && p->vline_labels[v])
                put(roi, ascii(p->vline_labels[v]), px + 5, 6, S_TICK, -1, -1, cv::Scalar(90, 90, 90));
        }
        /* solid coloured series first, then dashed ones (so a curve hidden under another
         * still shows through the gaps), the black reference last, on top */
        for (int pass = 0; pass < 3; pass++)
            for (int s = 0; s < p->nseries; s++) {
                const draw_series &se = p->series[s];
                int want = se.colour == DRAW_COLOUR_BLACK ? 2 : se.dashed ? 1 : 0;
                if (want != pass) continue;
                cv::Scalar col = palette(se.colour);
                std::vector<cv::Point2d> run;
                auto flush = [&]() {
                    if (!run.empty()) draw_polyline(roi, run, col, se.dashed != 0, 2);
                    run.clear();
                };
                for (int i = 0; i < se.count; i++) {
                    double x = se.x[i], y = se.y[i];
                    if (!usable(x, p->x_log) || !usable(y, p->y_log)) {
                        flush();
                        continue;
                    }
                    cv::Point2d q(ax.map(x) - plot.x, ay.map(y) - plot.y);
                    run.push_back(q);
                    if (se.markers && std::fabs(q.x) < 1e6 && std::fabs(q.y) < 1e6)
                        cv::circle(roi, cv::Point((int)std::lround(q.x), (int)std::lround(q.y)), 3, col, 1, cv::LINE_AA);
                }
                flush();
            }
        cv::rectangle(img, cv::Rect(plot.x - 1, plot.y - 1, plot.width + 2, plot.height + 2), INK, 1);

        if (nleg) {
            int lx = plot.x + plot.width + 16, ly = plot.y + 6;
            int lh = nleg * 26 + 10;
            cv::rectangle(img, cv::Rect(lx, ly, legend_w, lh), cv::Scalar(180, 180, 180), 1);
            int row = 0;
            for (int s = 0; s < p->nseries; s++) {
                const draw_series &se = p->series[s];
                if (!se.label) continue;
                int cy = ly + 18 + row * 26;
                std::vector<cv::Point2d> sample = {cv::Point2d(lx + 10, cy), cv::Point2d(lx + 48, cy)};
                draw_polyline(img, sample, palette(se.colour), se.dashed != 0, 2);
                if (se.markers) cv::circle(img, cv::Point(lx + 29, cy), 3, palette(se.colour), 1, cv::LINE_AA);
                put(img, ascii(se.label), lx + 58, cy, S_LABEL, -1, 0);
                row++;
            }
        }
        return img;
    });
}

namespace {

/* The value axis of a bar chart: linear from 0 to a rounded maximum, or logarithmic between the
 * decades around the smallest and largest positive values (so bars a thousand times apart both
 * show). */
Axis bar_axis(const struct draw_bar_chart *c, double vmin, double vmax, int x0, int x1)
{
    if (c->x_log) {
        if (!(vmin > 0)) vmin = vmax > 0 ? vmax / 10 : 1;
        if (!(vmax > 0)) vmax = 10;
        double lo = std::pow(10.0, std::floor(std::log10(vmin) + 1e-9));
        double hi = std::pow(10.0, std::ceil(std::log10(vmax) - 1e-9));
        if (!(hi > lo)) hi = lo * 10;
        return Axis{lo, hi, true, (double)x0, (double)x1};
    }
    if (!(vmax > 0)) vmax = 1;
    double step = nice_step(vmax / 6);
    return Axis{0, std::ceil(vmax / step - 1e-9) * step, false, (double)x0, (double)x1};
}

/* Log value axis: a labelled tick and grid line at each decade, short unlabelled ticks at 2..9. */
void draw_decade_ticks(cv::Mat &img, const Axis &a, int y, int grid_top)
{
    int e0 = (int)std::lround(std::log10(a.lo)), e1 = (int)std::lround(std::log10(a.hi));
    for (int e = e0; e <= e1; e++) {
        double v = std::pow(10.0, e);
        int px = (int)std::lround(a.map(v));
        cv::line(img, cv::Point(px, grid_top), cv::Point(px, y - 1), GRID, 1);
        cv::line(img, cv::Point(px, y), cv::Point(px, y + 6), INK, 1);
        put(img, tick_label(v, 0, DRAW_FMT_PLAIN), px, y + 9, S_TICK, 0, -1);
        for (int k = 2; e < e1 && k <= 9; k++) {
            int mx = (int)std::lround(a.map(k * v));
            cv::line(img, cv::Point(mx, y), cv::Point(mx, y + 3), INK, 1);
        }
    }
}

/* The value and whisker texts of the bars, the widest label and text, and the positive range. */
void bar_texts(const struct draw_bar_chart *c, std::vector<std::string> &texts, int *label_w, int *text_w,
               double *vmin, double *vmax)
{
    *vmin = INFINITY;
    *vmax = 0;
    *label_w = *text_w = 0;
    for (int i = 0; i < c->nbars; i++) {
        double v = c->values[i];
        char buf[64];
        if (c->value_text && c->value_text[i]) texts[i] = ascii(c->value_text[i]);
        else if (std::isfinite(v)) {
            snprintf(buf, sizeof buf, "%.3g", v);
            texts[i] = buf;
        } else texts[i] = "n/a";
        if (std::isfinite(v)) *vmax = std::max(*vmax, v);
        if (std::isfinite(v) && v > 0) *vmin = std::min(*vmin, v);
        if (c->err_hi && std::isfinite(c->err_hi[i])) *vmax = std::max(*vmax, c->err_hi[i]);
        if (c->err_lo && std::isfinite(c->err_lo[i]) && c->err_lo[i] > 0) *vmin = std::min(*vmin, c->err_lo[i]);
        *label_w = std::max(*label_w, text_size(ascii(c->labels[i]), S_LABEL).width);
        *text_w = std::max(*text_w, text_size(texts[i], S_TICK).width);
    }
}

} /* namespace */

extern "C" int draw_bar_chart(const char *path, const struct draw_bar_chart *c, char *err, size_t errlen)
{
    if (!check_path(path, err, errlen)) return -1;
    if (!c || c->nbars < 1 || c->nbars > 200 || !c->labels || !c->values) {
        set_err(err, errlen, "%s: a bar chart needs 1..200 labelled values", path);
        return -1;
    }
    return draw_png(path, err, errlen, [&]() -> cv::Mat {
        std::vector<std::string> texts(c->nbars);
        double vmin, vmax;
        int label_w, text_w;
        bar_texts(c, texts, &label_w, &text_w, &vmin, &vmax);
        std::string t = ascii(c->title);
        int th = title_height(t);
        int W = c->width > 0 ? c->width : 1000;
        int left = 16 + label_w + 12, right = text_w + 30;
        int row_h = 32, bottom = 70;
        W = std::max(W, left + right + 240);
        int H = th + 10 + c->nbars * row_h + bottom;
        cv::Mat img(H, W, CV_8UC3, WHITE);
        put_title(img, t);
        cv::Rect plot(left, th + 10, W - left - right, c->nbars * row_h);
        Axis ax = bar_axis(c, vmin, vmax, plot.x, plot.x + plot.width - 1);
        double xlo = ax.lo, xhi = ax.hi;
        if (c->x_log) draw_decade_ticks(img, ax, plot.y + plot.height, plot.y);
        else draw_x_ticks(img, ax, plot.y + plot.height, DRAW_FMT_PLAIN, 6, plot.y);
        put(img, ascii(c->x_label), plot.x + plot.width / 2, plot.y + plot.height + 36, S_LABEL, 0, -1);
        for (int i = 0; i < c->nbars; i++) {
            int y = plot.y + i * row_h;
            put(img, ascii(c->labels[i]), plot.x - 10, y + row_h / 2, S_LABEL, 1, 0);
            double v = c->values[i];
            int end = plot.x;
            if (std::isfinite(v) && v > 0) {
                end = (int)std::lround(ax.map(std::max(xlo, std::min(v, xhi))));
                cv::Scalar col = (i == c->highlight) ? cv::Scalar(60, 60, 60) : palette(0);
                cv::rectangle(img, cv::Rect(plot.x, y + 6, std::max(1, end - plot.x), row_h - 12), col, cv::FILLED);
            }
            if (c->err_lo && c->err_hi && std::isfinite(c->err_lo[i]) && std::isfinite(c->err_hi[i])) {
                double lo = c->x_log ? std::max(xlo, c->err_lo[i]) : std::max(0.0, c->err_lo[i]);
                int a = (int)std::lround(ax.map(std::min(xhi, lo)));
                int b = (int)std::lround(ax.map(std::max(xlo, std::min(xhi, c->err_hi[i]))));
                draw_error_bar(img, a, b, y + row_h / 2, 5);
                end = std::max(end, b);
            }
            put(img, texts[i], end + 6, y + row_h / 2, S_TICK, -1, 0);
        }
        cv::line(img, cv::Point(plot.x - 1, plot.y), cv::Point(plot.x - 1, plot.y + plot.height), INK, 1);
        cv::line(img, cv::Point(plot.x - 1, plot.y + plot.height), cv::Point(plot.x + plot.width, plot.y + plot.height), INK, 1);
        return img;
    });
}
