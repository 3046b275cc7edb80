/* draw.cpp - the pictures behind draw.h, drawn with OpenCV (core, imgproc, imgcodecs).
 *
 * The only C++ and the only OpenCV user in the host: everything crosses the extern "C"
 * interface of draw.h, every OpenCV exception is caught here and turned into -1 plus a
 * message. Text uses OpenCV's Hershey font, so strings are ASCII; a few UTF-8 symbols
 * that the model names and axis labels use (Greek letters, pi, <=, x) are spelled out.
 */
#include "draw.h"

extern "C" {
#include "infile.h"
#include "outdir.h"
}

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

/* ---- small helpers ------------------------------------------------------------ */

void set_err(char *err, size_t errlen, const char *fmt, ...)
{
    if (!err || errlen == 0) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
}

const cv::Scalar INK(40, 40, 40);          /* text and axes (BGR) */
const cv::Scalar GRID(225, 225, 225);
const cv::Scalar WHITE(255, 255, 255);
const cv::Scalar NODATA(100, 90, 90);      /* NaN cells / background pixels: RGB (90, 90, 100), a
                                              bluish grey no anti-aliased text pixel takes */
const int FONT = cv::FONT_HERSHEY_SIMPLEX;
const double S_TICK = 0.5, S_LABEL = 0.58, S_TITLE = 0.72;

/* Tableau 10, a palette that stays distinguishable for common colour-vision deficiencies. */
cv::Scalar palette(int i)
{
    static const unsigned char rgb[10][3] = {
        {31, 119, 180}, {255, 127, 14}, {44, 160, 44}, {214, 39, 40}, {148, 103, 189},
        {140, 86, 75}, {227, 119, 194}, {127, 127, 127}, {188, 189, 34}, {23, 190, 207}};
    if (i < 0) return cv::Scalar(0, 0, 0);
    const unsigned char *c = rgb[i % 10];
    return cv::Scalar(c[2], c[1], c[0]);
}

/* The palette's colours by name, in its order (draw_colour_index). */
const char *const palette_names[10] = {"blue", "orange", "green", "red", "purple",
                                       "brown", "pink", "grey", "olive", "cyan"};

/* UTF-8 to the ASCII the Hershey font can draw. */
std::string ascii(const char *s)
{
    static const struct { const char *utf8, *text; } map[] = {
        {"\xce\xb4", "delta"}, {"\xce\x94", "Delta"}, {"\xcf\x88", "psi"}, {"\xce\xb8", "theta"},
        {"\xcf\x80", "pi"}, {"\xce\xb1", "alpha"}, {"\xce\xbe", "xi"}, {"\xe2\x89\xa4", "<="},
        {"\xe2\x89\xa5", ">="}, {"\xc3\x97", "x"}, {"\xc2\xb7", "*"}, {"\xc2\xb2", "^2"},
        {"\xe2\x80\x93", "-"}, {"\xe2\x80\x94", "-"}, {"\xe2\x88\x92", "-"}, {"\xe2\x80\xa6", "..."},
        {"\xc2\xb5", "u"}, {"\xe2\x88\x9a", "sqrt"}, {"\xe2\x88\x88", "in"}};
    std::string out;
    if (!s) return out;
    for (size_t i = 0; s[i];) {
        unsigned char c = (unsigned char)s[i];
        if (c < 0x80) {
            out += (c == '\t') ? ' ' : (char)c;
            i++;
            continue;
        }
        bool done = false;
        for (const auto &m : map) {
            size_t n = strlen(m.utf8);
            if (strncmp(s + i, m.utf8, n) == 0) {
                out += m.text;
                i += n;
                done = true;
                break;
            }
        }
        if (done) continue;
        out += '?';
        i++; /* skip the continuation bytes of this code point */
        while (((unsigned char)s[i] & 0xC0) == 0x80) i++;
    }
    return out;
}

std::vector<std::string> split_lines(const std::string &s)
{
    std::vector<std::string> lines;
    size_t start = 0;
    for (;;) {
        size_t nl = s.find('\n', start);
        lines.push_back(s.substr(start, nl == std::string::npos ? std::string::npos : nl - start));
        if (nl == std::string::npos) break;
        start = nl + 1;
    }
    return lines;
}

cv::Size text_size(const std::string &t, double scale, int *baseline = nullptr)
{
    int b = 0;
    cv::Size sz = cv::getTextSize(t, FONT, scale, 1, &b);
    if (baseline) *baseline = b;
    return sz;
}

/* putText, except that '^' (which the Hershey font draws as a wave) becomes a caret drawn
 * with two strokes in the space of a blank, so "c^n" reads as it should. */
void hershey_text(cv::Mat &img, const std::string &t, cv::Point org, double scale, cv::Scalar colour, int thickness)
{
    std::string plain = t;
    for (char &c : plain)
        if (c == '^') c = ' ';
    cv::putText(img, plain, org, FONT, scale, colour, thickness, cv::LINE_AA);
    if (t.find('^') == std::string::npos) return;
    int cap = cv::getTextSize("M", FONT, scale, thickness, nullptr).height;
    int blank = cv::getTextSize("a b", FONT, scale, thickness, nullptr).width -
                cv::getTextSize("ab", FONT, scale, thickness, nullptr).width;
    for (size_t i = 0; i < t.size(); i++) {
        if (t[i] != '^') continue;
        int x0 = org.x + (i ? cv::getTextSize(plain.substr(0, i), FONT, scale, thickness, nullptr).width : 0);
        cv::Point a(x0 + 1, org.y - cap * 6 / 10), b(x0 + blank / 2, org.y - cap), c(x0 + blank - 1, org.y - cap * 6 / 10);
        cv::line(img, a, b, colour, thickness, cv::LINE_AA);
        cv::line(img, b, c, colour, thickness, cv::LINE_AA);
    }
}

/* Draw text; halign -1 left, 0 centre, 1 right of x; valign -1 top at y, 0 centred on y,
 * 1 baseline at y. */
void put(cv::Mat &img, const std::string &t, int x, int y, double scale, int halign, int valign,
         cv::Scalar colour = INK, int thickness = 1)
{
    if (t.empty()) return;
    cv::Size sz = text_size(t, scale);
    int px = x - (halign == 0 ? sz.width / 2 : halign > 0 ? sz.width : 0);
    int py = y + (valign < 0 ? sz.height : valign == 0 ? sz.height / 2 : 0);
    hershey_text(img, t, cv::Point(px, py), scale, colour, thickness);
}

/* Text rotated 90 degrees counter-clockwise (reads bottom to top), centred on (cx, cy). */
void put_vertical(cv::Mat &img, const std::string &t, int cx, int cy, double scale)
{
    if (t.empty()) return;
    int base = 0;
    cv::Size sz = text_size(t, scale, &base);
    cv::Mat tile(sz.height + base + 4, sz.width + 4, CV_8UC3, WHITE);
    hershey_text(tile, t, cv::Point(2, sz.height + 2), scale, INK, 1);
    cv::Mat rot;
    cv::rotate(tile, rot, cv::ROTATE_90_COUNTERCLOCKWISE);
    cv::Rect dst(cx - rot.cols / 2, cy - rot.rows / 2, rot.cols, rot.rows);
    cv::Rect clip = dst & cv::Rect(0, 0, img.cols, img.rows);
    if (clip.area() <= 0) return;
    cv::Mat src = rot(cv::Rect(clip.x - dst.x, clip.y - dst.y, clip.width, clip.height));
    /* darker-of blend, so the tile's white does not paint over anything */
    cv::Mat roi = img(clip);
    cv::min(roi, src, roi);
}

int title_height(const std::string &title)
{
    return 18 + 28 * (int)split_lines(title).size();
}

void put_title(cv::Mat &img, const std::string &title)
{
    std::vector<std::string> lines = split_lines(title);
    int y = 12;
    for (size_t i = 0; i < lines.size(); i++) {
        put(img, lines[i], img.cols / 2, y, i == 0 ? S_TITLE : S_LABEL, 0, -1, INK, i == 0 ? 2 : 1);
        y += 28;
    }
}

/* ---- colour maps ---------------------------------------------------------------- */

const cv::Mat &colormap_lut(int cmap)
{
    static cv::Mat luts[2];
    int k = (cmap == DRAW_CMAP_INFERNO) ? 1 : 0;
    if (luts[k].empty()) {
        cv::Mat ramp(1, 256, CV_8UC1);
        for (int i = 0; i < 256; i++) ramp.at<unsigned char>(0, i) = (unsigned char)i;
        cv::applyColorMap(ramp, luts[k], k ? cv::COLORMAP_INFERNO : cv::COLORMAP_VIRIDIS);
    }
    return luts[k];
}

cv::Vec3b cmap_bgr(int cmap, int index)
{
    index = std::max(0, std::min(255, index));
    return colormap_lut(cmap).at<cv::Vec3b>(0, index);
}

/* Colour-map index of v on [vmin, vmax]; the top of the scale is exactly 255. */
int value_index(double v, double vmin, double vmax)
{
    double t = (v - vmin) / (vmax - vmin);
    if (!(t > 0)) return 0;
    if (t >= 1) return 255;
    return (int)std::lround(t * 255.0);
}

/* ---- axes and ticks ------------------------------------------------------------- */

struct Axis {
    double lo, hi;
    bool log;
    double p0, p1; /* pixel of lo and of hi */
    double t(double v) const { return log ? std::log10(v) : v; }
    double map(double v) const { return p0 + (t(v) - t(lo)) / (t(hi) - t(lo)) * (p1 - p0); }
    bool inside(double v) const
    {
        double a = std::min(lo, hi), b = std::max(lo, hi);
        double eps = (b - a) * 1e-9;
        return std::isfinite(v) && v >= a - eps && v <= b + eps && (!log || v > 0);
    }
};

double nice_step(double raw)
{
    if (!(raw > 0) || !std::isfinite(raw)) return 1;
    double e = std::pow(10.0, std::floor(std::log10(raw)));
    double f = raw / e;
    double m = f <= 1 ? 1 : f <= 2 ? 2 : f <= 2.5 ? 2.5 : f <= 5 ? 5 : 10;
    return m * e;
}

std::vector<double> linear_ticks(double lo, double hi, int target, double *step_out)
{
    std::vector<double> ticks;
    double step = nice_step((hi - lo) / std::max(1, target));
    if (step_out) *step_out = step;
    double first = std::ceil(lo / step - 1e-9) * step;
    for (double v = first; v <= hi + step * 1e-9; v += step) {
        ticks.push_back(std::fabs(v) < step * 1e-9 ? 0.0 : v);
        if (ticks.size() > 50) break;
    }
    return ticks;
}

std::vector<double> log_ticks(double lo, double hi)
{
    std::vector<double> ticks;
    int e0 = (int)std::floor(std::log10(lo)) - 1, e1 = (int)std::ceil(std::log10(hi)) + 1;
    static const double m125[] = {1, 2, 5}, m1[] = {1};
    double decades = std::log10(hi / lo);
    const double *ms = decades <= 4 ? m125 : m1;
    int nm = decades <= 4 ? 3 : 1;
    for (int e = e0; e <= e1; e++)
        for (int k = 0; k < nm; k++) {
            double v = ms[k] * std::pow(10.0, e);
            if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) ticks.push_back(v);
        }
    if (ticks.size() < 2) { /* less than a decade: every integer multiple */
        ticks.clear();
        for (int e = e0; e <= e1; e++)
            for (int k = 1; k <= 9; k++) {
                double v = k * std::pow(10.0, e);
                if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) ticks.push_back(v);
            }
    }
    return ticks;
}

/* Label for a tick value; step (> 0) sets the decimals of linear ticks. */
std::string tick_label(double v, double step, int format)
{
    char buf[64];
    double scale = (format == DRAW_FMT_PERCENT) ? 100.0 : 1.0;
    double x = v * scale, s = step * scale;
    const char *suffix = (format == DRAW_FMT_PERCENT) ? "%" : "";
    double ax = std::fabs(x);
    if (s > 0 && ax < 1e5 && (ax >= 1e-3 || x == 0)) {
        int dec = std::max(0, (int)std::ceil(-std::log10(s) - 1e-9));
        if (std::fabs(s * std::pow(10.0, dec) - std::round(s * std::pow(10.0, dec))) > 1e-6) dec++;
        dec = std::min(dec, 6);
        snprintf(buf, sizeof buf, "%.*f%s", dec, x, suffix);
    } else if (x == std::round(x) && ax < 1e7) {
        snprintf(buf, sizeof buf, "%.0f%s", x, suffix); /* log-axis ticks: 1000, not 1e+03 */
    } else {
        snprintf(buf, sizeof buf, "%.3g%s", x, suffix);
    }
    return buf;
}

std::vector<double> axis_ticks(const Axis &a, int target, double *step)
{
    double lo = std::min(a.lo, a.hi), hi = std::max(a.lo, a.hi);
    if (a.log) {
        if (step) *step = 0;
        return log_ticks(lo, hi);
    }
    return linear_ticks(lo, hi, target, step);
}

/* Tick marks and labels below a horizontal axis at pixel row y. */
void draw_x_ticks(cv::Mat &img, const Axis &a, int y, int format, int target, int grid_top = -1)
{
    double step = 0;
    for (double v : axis_ticks(a, target, &step)) {
        int px = (int)std::lround(a.map(v));
        if (grid_top >= 0) cv::line(img, cv::Point(px, grid_top), cv::Point(px, y - 1), GRID, 1);
        cv::line(img, cv::Point(px, y), cv::Point(px, y + 5), INK, 1);
        put(img, tick_label(v, step, format), px, y + 9, S_TICK, 0, -1);
    }
}

/* Tick marks and labels left of a vertical axis at pixel column x; returns the widest label. */
int draw_y_ticks(cv::Mat &img, const Axis &a, int x, int format, int target, int grid_right = -1)
{
    double step = 0;
    int widest = 0;
    for (double v : axis_ticks(a, target, &step)) {
        int py = (int)std::lround(a.map(v));
        if (grid_right >= 0) cv::line(img, cv::Point(x + 1, py), cv::Point(grid_right, py), GRID, 1);
        cv::line(img, cv::Point(x - 5, py), cv::Point(x, py), INK, 1);
        std::string t = tick_label(v, step, format);
        widest = std::max(widest, text_size(t, S_TICK).width);
        put(img, t, x - 8, py, S_TICK, 1, 0);
    }
    return widest;
}

int y_label_width(const Axis &a, int format, int target)
{
    double step = 0;
    int widest = 0;
    for (double v : axis_ticks(a, target, &step))
        widest = std::max(widest, text_size(tick_label(v, step, format), S_TICK).width);
    return widest;
}

/* Vertical colour bar at rect (top = vmax) with ticks and labels to its right and the
 * caption rotated beside them. */
void draw_colour_bar(cv::Mat &img, cv::Rect r, int cmap, double vmin, double vmax, int format,
                     const std::string &caption)
{
    for (int y = 0; y < r.height; y++) {
        /* bottom row = index 0, top row = index 255 */
        int idx = r.height > 1 ? (int)std::lround(255.0 * (r.height - 1 - y) / (r.height - 1)) : 255;
        cv::Vec3b c = cmap_bgr(cmap, idx);
        cv::line(img, cv::Point(r.x, r.y + y), cv::Point(r.x + r.width - 1, r.y + y),
                 cv::Scalar(c[0], c[1], c[2]), 1);
    }
    cv::rectangle(img, cv::Rect(r.x - 1, r.y - 1, r.width + 2, r.height + 2), INK, 1);
    Axis a{vmin, vmax, false, (double)(r.y + r.height - 1), (double)r.y};
    double step = 0;
    int widest = 0;
    for (double v : linear_ticks(vmin, vmax, 6, &step)) {
        int py = (int)std::lround(a.map(v));
        cv::line(img, cv::Point(r.x + r.width, py), cv::Point(r.x + r.width + 5, py), INK, 1);
        std::string t = tick_label(v, step, format);
        widest = std::max(widest, text_size(t, S_TICK).width);
        put(img, t, r.x + r.width + 8, py, S_TICK, -1, 0);
    }
    put_vertical(img, caption, r.x + r.width + 8 + widest + 16, r.y + r.height / 2, S_LABEL);
}

int colour_bar_extent(double vmin, double vmax, int format, int bar_w)
{
    double step = 0;
    int widest = 0;
    for (double v : linear_ticks(vmin, vmax, 6, &step))
        widest = std::max(widest, text_size(tick_label(v, step, format), S_TICK).width);
    return bar_w + 8 + widest + 16 + 14;
}

/* Scale for a colour bar: the caller's [vmin, vmax] or [0, data max]; never empty. */
void colour_scale(double vmin, double vmax, double data_max, double *lo, double *hi)
{
    if (std::isfinite(vmin) && std::isfinite(vmax) && vmax > vmin) {
        *lo = vmin;
        *hi = vmax;
        return;
    }
    *lo = 0;
    *hi = (std::isfinite(data_max) && data_max > 0) ? data_max : 1;
}

/* ---- writing --------------------------------------------------------------------- */

int write_png(const char *path, const cv::Mat &bgr, char *err, size_t errlen)
{
    std::vector<unsigned char> buf;
    if (!cv::imencode(".png", bgr, buf)) {
        set_err(err, errlen, "%s: PNG encoding failed", path);
        return -1;
    }
    char why[512] = "";
    if (write_file_atomic(path, buf.data(), buf.size(), why, sizeof why) != 0) {
        set_err(err, errlen, "%s", why[0] ? why : "cannot write file");
        if (!strstr(err, path)) {
            std::string msg = std::string(path) + ": " + why;
            set_err(err, errlen, "%s", msg.c_str());
        }
        return -1;
    }
    return 0;
}

/* A horizontal error bar from x = a to b at height cy, with end ticks of half-height tick. */
static void draw_error_bar(cv::Mat &img, int a, int b, int cy, int tick)
{
    cv::line(img, cv::Point(a, cy), cv::Point(b, cy), INK, 1);
    cv::line(img, cv::Point(a, cy - tick), cv::Point(a, cy + tick), INK, 1);
    cv::line(img, cv::Point(b, cy - tick), cv::Point(b, cy + tick), INK, 1);
}

/* The image that draw() makes, written to path as PNG; an OpenCV exception on the way becomes
 * the error "path: what", -1. */
template <class Draw> static int draw_png(const char *path, char *err, size_t errlen, Draw draw)
{
    try {
        cv::Mat img = draw();
        return write_png(path, img, err, errlen);
    } catch (const std::exception &e) {
        set_err(err, errlen, "%s: %s", path, e.what());
        return -1;
    }
}

bool check_path(const char *path, char *err, size_t errlen)
{
    if (!path || !*path) {
        set_err(err, errlen, "picture path is empty");
        return false;
    }
    return true;
}

/* ---- error images ------------------------------------------------------------------- */

double finite_max(const float *v, size_t n)
{
    double m = NAN;
    for (size_t i = 0; i < n; i++)
        if (std::isfinite(v[i]) && !(v[i] <= m)) m = v[i];
    return m;
}

/* False-colour an error image into dst (BGR, width x height). */
void error_to_bgr(const float *e, int w, int h, double lo, double hi, cv::Mat dst)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float v = e[(size_t)y * w + x];
            if (!std::isfinite(v)) {
                dst.at<cv::Vec3b>(y, x) = cv::Vec3b((uchar)NODATA[0], (uchar)NODATA[1], (uchar)NODATA[2]);
            } else {
                dst.at<cv::Vec3b>(y, x) = cmap_bgr(DRAW_CMAP_INFERNO, value_index(v, lo, hi));
            }
        }
}

void rgb_to_bgr(const unsigned char *rgb, int w, int h, cv::Mat dst)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const unsigned char *p = rgb + ((size_t)y * w + x) * 3;
            dst.at<cv::Vec3b>(y, x) = cv::Vec3b(p[2], p[1], p[0]);
        }
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

/* Images of width x height (count of them) in a row, captions above, the error colour bar
 * on the right; the last image is the error. */
cv::Mat image_row(int w, int h, const unsigned char *ref_rgb, const unsigned char *model_rgb,
                  const float *abs_err, float vmax, const char *title)
{
    bool sheet = ref_rgb != nullptr;
    double lo, hi;
    colour_scale(0, vmax, finite_max(abs_err, (size_t)w * h), &lo, &hi);
    const int M = 12, GAP = 12, BAR_W = 20, BAR_MIN_H = 220;
    int nimg = sheet ? 3 : 1;
    std::string t = ascii(title);
    int th = title_height(t);
    int cap_h = sheet ? 26 : 0;
    int bar_h = std::max(h, BAR_MIN_H);
    int bar_extent = colour_bar_extent(lo, hi, DRAW_FMT_PLAIN, BAR_W);
    static const char *captions[3] = {"reference", "model", "abs. error"};
    /* each image sits centred in a slot at least as wide as its caption */
    int slot = w;
    if (sheet)
        for (int k = 0; k < 3; k++) slot = std::max(slot, text_size(captions[k], S_LABEL).width + 8);
    int width = M + nimg * slot + (nimg - 1) * GAP + 18 + bar_extent + M;
    int title_w = 0;
    for (const std::string &l : split_lines(t)) title_w = std::max(title_w, text_size(l, S_TITLE).width + 2 * M);
    width = std::max(width, title_w);
    int height = th + cap_h + bar_h + M;
    cv::Mat img(height, width, CV_8UC3, WHITE);
    put_title(img, t);
    int y0 = th + cap_h;
    for (int k = 0; k < nimg; k++) {
        int sx = M + k * (slot + GAP), x0 = sx + (slot - w) / 2;
        cv::Mat dst = img(cv::Rect(x0, y0, w, h));
        if (sheet && k == 0) rgb_to_bgr(ref_rgb, w, h, dst);
        else if (sheet && k == 1) rgb_to_bgr(model_rgb, w, h, dst);
        else error_to_bgr(abs_err, w, h, lo, hi, dst);
        if (sheet) put(img, captions[k], sx + slot / 2, y0 - 6, S_LABEL, 0, 1);
    }
    int bx = M + nimg * slot + (nimg - 1) * GAP + 18;
    draw_colour_bar(img, cv::Rect(bx, y0, BAR_W, bar_h), DRAW_CMAP_INFERNO, lo, hi, DRAW_FMT_PLAIN,
                    "absolute error");
    return img;
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

/* ---- line plots --------------------------------------------------------------------- */

bool usable(double v, bool log) { return std::isfinite(v) && (!log || v > 0); }

/* Liang-Barsky: clips the segment a-b to the box [x0, x1] x [y0, y1]; false when nothing of it
 * (or a non-finite end) is inside. */
static bool clip_segment(cv::Point2d &a, cv::Point2d &b, double x0, double y0, double x1, double y1)
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

/* ==== extern "C" interface ================================================================ */

extern "C" int draw_colour_index(const char *name)
{
    if (name && strcmp(name, "black") == 0) return DRAW_COLOUR_BLACK;
    for (int i = 0; name && i < 10; i++)
        if (strcmp(name, palette_names[i]) == 0) return i;
    return DRAW_COLOUR_UNKNOWN;
}

extern "C" void draw_colormap_rgb(int cmap, int index, unsigned char rgb[3])
{
    try {
        cv::Vec3b c = cmap_bgr(cmap, index);
        rgb[0] = c[2];
        rgb[1] = c[1];
        rgb[2] = c[0];
    } catch (...) {
        rgb[0] = rgb[1] = rgb[2] = 0;
    }
}

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
                    [&]() { return image_row(width, height, nullptr, nullptr, abs_err, vmax, title); });
}

extern "C" int draw_contact_sheet(const char *path, int width, int height, const unsigned char *ref_rgb,
                                  const unsigned char *model_rgb, const float *abs_err, float vmax,
                                  const char *title, char *err, size_t errlen)
{
    if (!check_image_args(path, width, height, abs_err, "error", err, errlen)) return -1;
    if (!ref_rgb || !model_rgb) {
        set_err(err, errlen, "%s: contact sheet needs both the reference and the model image", path);
        return -1;
    }
    return draw_png(path, err, errlen,
                    [&]() { return image_row(width, height, ref_rgb, model_rgb, abs_err, vmax, title); });
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
            const draw_heatmap_panel &p = panels[k];
            PanelGeom &g = geom[k];
            double fmax = finite_max(p.values, (size_t)p.cols * p.rows), lo, hi;
            colour_scale(p.vmin, p.vmax, fmax, &lo, &hi);
            Axis ay{p.y_min, p.y_max, p.y_log != 0, 0, 1};
            g.left = 8 + 24 + y_label_width(ay, DRAW_FMT_PLAIN, 6) + 8 + 8;
            g.plot_w = HM_PLOT_W;
            g.plot_h = HM_PLOT_H;
            g.bar_gap = 20;
            g.bar_w = HM_BAR_W;
            g.bar_extent = colour_bar_extent(lo, hi, p.value_format, HM_BAR_W);
            g.width = g.left + g.plot_w + g.bar_gap + g.bar_extent + 16;
            total_w += g.width;
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

extern "C" int draw_bar_chart(const char *path, const struct draw_bar_chart *c, char *err, size_t errlen)
{
    if (!check_path(path, err, errlen)) return -1;
    if (!c || c->nbars < 1 || c->nbars > 200 || !c->labels || !c->values) {
        set_err(err, errlen, "%s: a bar chart needs 1..200 labelled values", path);
        return -1;
    }
    return draw_png(path, err, errlen, [&]() -> cv::Mat {
        std::vector<std::string> texts(c->nbars);
        double vmax = 0;
        int label_w = 0, text_w = 0;
        for (int i = 0; i < c->nbars; i++) {
            double v = c->values[i];
            char buf[64];
            if (c->value_text && c->value_text[i]) texts[i] = ascii(c->value_text[i]);
            else if (std::isfinite(v)) {
                snprintf(buf, sizeof buf, "%.3g", v);
                texts[i] = buf;
            } else texts[i] = "n/a";
            if (std::isfinite(v)) vmax = std::max(vmax, v);
            if (c->err_hi && std::isfinite(c->err_hi[i])) vmax = std::max(vmax, c->err_hi[i]);
            label_w = std::max(label_w, text_size(ascii(c->labels[i]), S_LABEL).width);
            text_w = std::max(text_w, text_size(texts[i], S_TICK).width);
        }
        if (!(vmax > 0)) vmax = 1;
        double step = nice_step(vmax / 6);
        double xhi = std::ceil(vmax / step - 1e-9) * step;
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
        Axis ax{0, xhi, false, (double)plot.x, (double)(plot.x + plot.width - 1)};
        draw_x_ticks(img, ax, plot.y + plot.height, DRAW_FMT_PLAIN, 6, plot.y);
        put(img, ascii(c->x_label), plot.x + plot.width / 2, plot.y + plot.height + 36, S_LABEL, 0, -1);
        for (int i = 0; i < c->nbars; i++) {
            int y = plot.y + i * row_h;
            put(img, ascii(c->labels[i]), plot.x - 10, y + row_h / 2, S_LABEL, 1, 0);
            double v = c->values[i];
            int end = plot.x;
            if (std::isfinite(v) && v > 0) {
                end = (int)std::lround(ax.map(std::min(v, xhi)));
                cv::Scalar col = (i == c->highlight) ? cv::Scalar(60, 60, 60) : palette(0);
                cv::rectangle(img, cv::Rect(plot.x, y + 6, std::max(1, end - plot.x), row_h - 12), col, cv::FILLED);
            }
            if (c->err_lo && c->err_hi && std::isfinite(c->err_lo[i]) && std::isfinite(c->err_hi[i])) {
                int a = (int)std::lround(ax.map(std::max(0.0, c->err_lo[i])));
                int b = (int)std::lround(ax.map(std::min(xhi, c->err_hi[i])));
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

extern "C" int draw_read_rgb8(const char *path, int *width, int *height, unsigned char **rgb, char *err,
                              size_t errlen)
{
    if (!check_path(path, err, errlen)) return -1;
    char why[256];
    int fd = infile_open(path, 0, NULL, why, sizeof why); /* a clear message, no warning from imread, no FIFO */
    if (fd < 0) {
        set_err(err, errlen, "%s: %s", path, why);
        return -1;
    }
    close(fd);
    try {
        cv::Mat img = cv::imread(path, cv::IMREAD_COLOR);
        if (img.empty()) {
            set_err(err, errlen, "%s: cannot be read or decoded as an image", path);
            return -1;
        }
        size_t n = (size_t)img.cols * img.rows * 3;
        unsigned char *buf = (unsigned char *)malloc(n);
        if (!buf) {
            set_err(err, errlen, "%s: out of memory", path);
            return -1;
        }
        for (int y = 0; y < img.rows; y++)
            for (int x = 0; x < img.cols; x++) {
                cv::Vec3b c = img.at<cv::Vec3b>(y, x);
                unsigned char *q = buf + ((size_t)y * img.cols + x) * 3;
                q[0] = c[2];
                q[1] = c[1];
                q[2] = c[0];
            }
        *width = img.cols;
        *height = img.rows;
        *rgb = buf;
        return 0;
    } catch (const std::exception &e) {
        set_err(err, errlen, "%s: %s", path, e.what());
        return -1;
    }
}

extern "C" int draw_ratio_chart(const char *path, const struct draw_ratio_chart *c, char *err, size_t errlen)
{
    if (!check_path(path, err, errlen)) return -1;
    if (!c || c->ngroups < 1 || c->nseries < 1 || c->ngroups * c->nseries > 2000 || !c->groups || !c->series ||
        !c->values) {
        set_err(err, errlen, "%s: a ratio chart needs 1..2000 bars in labelled groups", path);
        return -1;
    }
    return draw_png(path, err, errlen, [&]() -> cv::Mat {
        const int G = c->ngroups, S = c->nseries;
        double vmax = 1;
        int label_w = 0, text_w = 0, legend_w = 0;
        std::vector<std::string> texts((size_t)G * S);
        for (int i = 0; i < G * S; i++) {
            double v = c->values[i];
            char buf[64];
            if (std::isfinite(v)) {
                snprintf(buf, sizeof buf, "%.3fx", v);
                texts[i] = buf;
                vmax = std::max(vmax, v);
            } else texts[i] = "n/a";
            if (c->err_hi && std::isfinite(c->err_hi[i])) vmax = std::max(vmax, c->err_hi[i]);
            text_w = std::max(text_w, text_size(texts[i], S_TICK).width);
        }
        for (int g = 0; g < G; g++) {
            label_w = std::max(label_w, text_size(ascii(c->groups[g]), S_LABEL).width);
            if (c->band_hi && std::isfinite(c->band_hi[g])) vmax = std::max(vmax, c->band_hi[g]);
        }
        for (int s = 0; s < S; s++) legend_w += text_size(ascii(c->series[s]), S_LABEL).width + 46;
        vmax = std::min(vmax, 1e6);
        double step = nice_step(vmax * 1.05 / 6);
        double xhi = std::ceil(vmax * 1.05 / step - 1e-9) * step;
        std::string t = ascii(c->title);
        int th = title_height(t);
        int W = c->width > 0 ? c->width : 1000;
        int left = 16 + label_w + 12, right = text_w + 30;
        int bar_h = 16, gap = 12, legend_h = 34, bottom = 70;
        W = std::max({W, left + right + 240, legend_w + 40});
        int group_h = S * bar_h + gap;
        int H = th + legend_h + G * group_h + bottom;
        cv::Mat img(H, W, CV_8UC3, WHITE);
        put_title(img, t);
        /* legend: one swatch per run */
        int lx = 20, ly = th + legend_h / 2;
        for (int s = 0; s < S; s++) {
            cv::rectangle(img, cv::Rect(lx, ly - 7, 30, 14), s == 0 ? cv::Scalar(60, 60, 60) : palette(s - 1), cv::FILLED);
            std::string name = ascii(c->series[s]);
            put(img, name, lx + 38, ly, S_LABEL, -1, 0);
            lx += 46 + text_size(name, S_LABEL).width;
        }
        cv::Rect plot(left, th + legend_h, W - left - right, G * group_h);
        Axis ax{0, xhi, false, (double)plot.x, (double)(plot.x + plot.width - 1)};
        for (int g = 0; g < G; g++) {
            int y0 = plot.y + g * group_h;
            if (c->band_lo && c->band_hi && std::isfinite(c->band_lo[g]) && std::isfinite(c->band_hi[g])) {
                int a = (int)std::lround(ax.map(std::max(0.0, std::min(xhi, c->band_lo[g]))));
                int b = (int)std::lround(ax.map(std::max(0.0, std::min(xhi, c->band_hi[g]))));
                cv::rectangle(img, cv::Rect(a, y0, std::max(1, b - a), S * bar_h), cv::Scalar(215, 215, 215), cv::FILLED);
            }
        }
        draw_x_ticks(img, ax, plot.y + plot.height, DRAW_FMT_PLAIN, 6, plot.y);
        put(img, ascii(c->x_label), plot.x + plot.width / 2, plot.y + plot.height + 36, S_LABEL, 0, -1);
        for (int g = 0; g < G; g++) {
            int y0 = plot.y + g * group_h;
            put(img, ascii(c->groups[g]), plot.x - 10, y0 + S * bar_h / 2, S_LABEL, 1, 0);
            for (int s = 0; s < S; s++) {
                int i = g * S + s, y = y0 + s * bar_h;
                double v = c->values[i];
                int end = plot.x;
                if (std::isfinite(v) && v > 0) {
                    end = (int)std::lround(ax.map(std::min(v, xhi)));
                    cv::Scalar col = s == 0 ? cv::Scalar(60, 60, 60) : palette(s - 1);
                    cv::rectangle(img, cv::Rect(plot.x, y + 2, std::max(1, end - plot.x), bar_h - 4), col, cv::FILLED);
                }
                if (c->err_lo && c->err_hi && std::isfinite(c->err_lo[i]) && std::isfinite(c->err_hi[i])) {
                    int a = (int)std::lround(ax.map(std::max(0.0, std::min(xhi, c->err_lo[i]))));
                    int b = (int)std::lround(ax.map(std::max(0.0, std::min(xhi, c->err_hi[i]))));
                    draw_error_bar(img, a, b, y + bar_h / 2, 4);
                    end = std::max(end, b);
                }
                put(img, texts[i], end + 6, y + bar_h / 2, S_TICK, -1, 0);
            }
        }
        /* 1 = the baseline, dashed */
        int x1 = (int)std::lround(ax.map(1.0));
        for (int y = plot.y; y < plot.y + plot.height; y += 8)
            cv::line(img, cv::Point(x1, y), cv::Point(x1, std::min(y + 4, plot.y + plot.height)), INK, 1);
        cv::line(img, cv::Point(plot.x - 1, plot.y), cv::Point(plot.x - 1, plot.y + plot.height), INK, 1);
        cv::line(img, cv::Point(plot.x - 1, plot.y + plot.height), cv::Point(plot.x + plot.width, plot.y + plot.height), INK, 1);
        return img;
    });
}

/* ---- scatter plots ------------------------------------------------------------------------ */

static int scatter_plot(const char *path, const struct draw_scatter *plot, bool legend, char *err, size_t errlen)
{
    return draw_png(path, err, errlen, [&]() -> cv::Mat {
        const int W = 1100, H = 720, left = 110, right = 40, top = title_height(plot->title) + 20, bottom = 80;
        cv::Mat img(H, W, CV_8UC3, WHITE);
        put_title(img, plot->title);
        double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
        for (int i = 0; i < plot->count; i++) {
            if (std::isfinite(plot->x[i]) && plot->x[i] > 0) {
                xlo = std::min(xlo, plot->x[i]);
                xhi = std::max(xhi, plot->x[i]);
            }
            if (std::isfinite(plot->y[i]) && plot->y[i] > 0) {
                ylo = std::min(ylo, plot->y[i]);
                yhi = std::max(yhi, plot->y[i]);
            }
        }
        if (!(xhi > 0)) { xlo = 1e-3; xhi = 1; }
        if (!(yhi > 0)) { ylo = 1; yhi = 10; }
        /* a decade-aligned margin; the floor leaves room for the exact references */
        xlo = std::pow(10.0, std::floor(std::log10(xlo)) - 1);
        xhi = std::pow(10.0, std::ceil(std::log10(xhi) + 0.05));
        ylo = std::pow(10.0, std::floor(std::log10(ylo) - 0.05));
        yhi = std::pow(10.0, std::ceil(std::log10(yhi) + 0.05));
        Axis ax{xlo, xhi, true, (double)left, (double)(W - right)};
        Axis ay{ylo, yhi, true, (double)(H - bottom), (double)top};
        cv::rectangle(img, cv::Point(left, top), cv::Point(W - right, H - bottom), INK, 1);
        draw_x_ticks(img, ax, H - bottom, plot->x_format, 6, top);
        draw_y_ticks(img, ay, left, DRAW_FMT_PLAIN, 6, W - right);
        put(img, plot->x_label, (left + W - right) / 2, H - 30, S_LABEL, 0, -1);
        put_vertical(img, plot->y_label, 22, (top + H - bottom) / 2, S_LABEL);
        auto px = [&](int i) {
            double xv = (std::isfinite(plot->x[i]) && plot->x[i] > 0) ? plot->x[i] : xlo;
            return cv::Point((int)std::lround(ax.map(xv)), (int)std::lround(ay.map(plot->y[i])));
        };
        /* the front, joined in order of x */
        std::vector<int> fr;
        for (int i = 0; i < plot->count; i++)
            if (plot->front[i] && std::isfinite(plot->y[i]) && plot->y[i] > 0) fr.push_back(i);
        std::sort(fr.begin(), fr.end(), [&](int a, int b) { return px(a).x < px(b).x; });
        for (size_t k = 1; k < fr.size(); k++)
            cv::line(img, px(fr[k - 1]), px(fr[k]), palette(3), 2, cv::LINE_AA);
        /* labels placed greedily: the first of a few spots beside the point that overlaps no
           label or mark placed before it */
        std::vector<cv::Rect> taken;
        for (int i = 0; i < plot->count; i++)
            if (std::isfinite(plot->y[i]) && plot->y[i] > 0) taken.push_back(cv::Rect(px(i) - cv::Point(6, 6), cv::Size(13, 13)));
        for (int i = 0; i < plot->count; i++) {
            if (!(std::isfinite(plot->y[i]) && plot->y[i] > 0)) continue;
            cv::Point p = px(i);
            cv::Scalar col = plot->marks[i] == DRAW_MARK_REFERENCE ? INK
                             : plot->marks[i] == DRAW_MARK_PAPER   ? palette(0)
                                                                   : palette(1);
            if (plot->marks[i] == DRAW_MARK_REFERENCE) {
                cv::rectangle(img, p - cv::Point(5, 5), p + cv::Point(5, 5), col, cv::FILLED);
            } else if (plot->marks[i] == DRAW_MARK_PAPER) {
                std::vector<cv::Point> tri{p + cv::Point(0, -7), p + cv::Point(6, 5), p + cv::Point(-6, 5)};
                cv::fillConvexPoly(img, tri, col, cv::LINE_AA);
            } else {
                cv::circle(img, p, 5, col, cv::FILLED, cv::LINE_AA);
            }
            if (plot->front[i]) cv::circle(img, p, 9, palette(3), 2, cv::LINE_AA);
            cv::Size ts = text_size(plot->labels[i], S_TICK);
            static const int dx[] = { 10, 10, -10, -10, 10, -10, 10, -10, 0, 0 };
            static const int dy[] = { -8, 8, -8, 8, -22, -22, 22, 22, -34, 34 };
            int best = 0;
            for (int k = 0; k < 10; k++) {
                int x0 = dx[k] > 0 ? p.x + dx[k] : dx[k] < 0 ? p.x + dx[k] - ts.width : p.x - ts.width / 2;
                cv::Rect box(x0, p.y + dy[k] - ts.height / 2 - 1, ts.width, ts.height + 2);
                bool clear = box.x >= left && box.x + box.width <= W - right && box.y >= top && box.y + box.height <= H - bottom;
                for (const cv::Rect &o : taken)
                    if (clear && (box & o).area() > 0) clear = false;
                if (clear) { best = k; break; }
            }
            int x0 = dx[best] > 0 ? p.x + dx[best] : dx[best] < 0 ? p.x + dx[best] - ts.width : p.x - ts.width / 2;
            taken.push_back(cv::Rect(x0, p.y + dy[best] - ts.height / 2 - 1, ts.width, ts.height + 2));
            put(img, plot->labels[i], x0, p.y + dy[best], S_TICK, -1, 0);
        }
        /* legend */
        if (!legend) return img;
        int lx = left + 12, ly = top + 14;
        cv::rectangle(img, cv::Point(lx - 5, ly - 5), cv::Point(lx + 5, ly + 5), INK, cv::FILLED);
        put(img, "reference (exact: drawn at the axis floor)", lx + 14, ly, S_TICK, -1, 0);
        std::vector<cv::Point> tri{cv::Point(lx, ly + 13), cv::Point(lx + 6, ly + 25), cv::Point(lx - 6, ly + 25)};
        cv::fillConvexPoly(img, tri, palette(0), cv::LINE_AA);
        put(img, "the papers' models", lx + 14, ly + 20, S_TICK, -1, 0);
        cv::circle(img, cv::Point(lx, ly + 40), 5, palette(1), cv::FILLED, cv::LINE_AA);
        put(img, "engines' approximations and tuned models", lx + 14, ly + 40, S_TICK, -1, 0);
        cv::circle(img, cv::Point(lx, ly + 60), 9, palette(3), 2, cv::LINE_AA);
        put(img, "on the front (joined)", lx + 14, ly + 60, S_TICK, -1, 0);
        return img;
    });
}

int draw_scatter_plot(const char *path, const struct draw_scatter *plot, char *err, size_t errlen)
{
    return scatter_plot(path, plot, true, err, errlen);
}

int draw_scatter_plot_plain(const char *path, const struct draw_scatter *plot, char *err, size_t errlen)
{
    return scatter_plot(path, plot, false, err, errlen);
}
