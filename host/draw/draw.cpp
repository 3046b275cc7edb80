/* draw.cpp - the parts of the pictures behind draw.h that every picture shares (draw_common.hpp),
 * the colour maps and reading a PNG back; the pictures themselves are in draw_image.cpp (images,
 * heatmaps), draw_plot.cpp (line plots, bar charts), draw_chart.cpp (scatter plots) and
 * draw_compare.cpp (compare's verdict chart).
 *
 * The only C++ and the only OpenCV user in the host: everything crosses the extern "C"
 * interface of draw.h, every OpenCV exception is caught here and turned into -1 plus a
 * message. Text uses OpenCV's Hershey font, so strings are ASCII; a few UTF-8 symbols
 * that the model names and axis labels use (Greek letters, pi, <=, x) are spelled out.
 */
#include "draw_common.hpp"

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

namespace draw_detail {

/* ---- small helpers ------------------------------------------------------------ */

void set_err(char *err, size_t errlen, const char *fmt, ...)
{
    if (!err || errlen == 0) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
}

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
static const char *const palette_names[10] = {"blue", "orange", "green", "red", "purple",
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

std::vector<std::string> split_on(const std::string &s, const std::string &sep)
{
    std::vector<std::string> parts;
    size_t start = 0;
    for (;;) {
        size_t at = s.find(sep, start);
        parts.push_back(s.substr(start, at == std::string::npos ? std::string::npos : at - start));
        if (at == std::string::npos) break;
        start = at + sep.size();
    }
    return parts;
}

std::vector<std::string> split_lines(const std::string &s) { return split_on(s, "\n"); }

cv::Size text_size(const std::string &t, double scale, int *baseline)
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
         cv::Scalar colour, int thickness)
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

/* Blue (RGB 33, 102, 172) at 0, white at 128, red (RGB 178, 24, 43) at 255, linear between:
 * the ends of ColorBrewer's RdBu. */
void diverging_lut(cv::Mat &lut)
{
    static const double blue[3] = {172, 102, 33}, red[3] = {43, 24, 178};   /* BGR */
    lut.create(1, 256, CV_8UC3);
    for (int i = 0; i < 256; i++) {
        const double *end = i < 128 ? blue : red;
        double t = i < 128 ? (128 - i) / 128.0 : (i - 128) / 127.0;
        cv::Vec3b c;
        for (int k = 0; k < 3; k++) c[k] = (uchar)std::lround(255 + t * (end[k] - 255));
        lut.at<cv::Vec3b>(0, i) = c;
    }
}

const cv::Mat &colormap_lut(int cmap)
{
    static cv::Mat luts[3];
    int k = cmap == DRAW_CMAP_INFERNO ? 1 : cmap == DRAW_CMAP_DIVERGING ? 2 : 0;
    if (k == 2 && luts[k].empty()) diverging_lut(luts[k]);
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
void draw_x_ticks(cv::Mat &img, const Axis &a, int y, int format, int target, int grid_top)
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
int draw_y_ticks(cv::Mat &img, const Axis &a, int x, int format, int target, int grid_right)
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

bool check_path(const char *path, char *err, size_t errlen)
{
    if (!path || !*path) {
        set_err(err, errlen, "picture path is empty");
        return false;
    }
    return true;
}

/* A horizontal error bar from x = a to b at height cy, with end ticks of half-height tick. */
void draw_error_bar(cv::Mat &img, int a, int b, int cy, int tick)
{
    cv::line(img, cv::Point(a, cy), cv::Point(b, cy), INK, 1);
    cv::line(img, cv::Point(a, cy - tick), cv::Point(a, cy + tick), INK, 1);
    cv::line(img, cv::Point(b, cy - tick), cv::Point(b, cy + tick), INK, 1);
}


/* RGB row-major bytes into a BGR picture of w x h. */
void rgb_to_bgr(const unsigned char *rgb, int w, int h, cv::Mat dst)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const unsigned char *p = rgb + ((size_t)y * w + x) * 3;
            dst.at<cv::Vec3b>(y, x) = cv::Vec3b(p[2], p[1], p[0]);
        }
}

} /* namespace draw_detail */

using namespace draw_detail;

/* ==== extern "C" interface ================================================================ */

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

/* The band under a picture that says its run is not for figures: pale amber, dark red text,
 * centred, the font shrunk until the text fits the picture's width. */
static cv::Mat stamped(const cv::Mat &img, const std::string &text)
{
    double scale = S_LABEL;
    while (scale > 0.3 && text_size(text, scale).width + 16 > img.cols) scale -= 0.02;
    int band = text_size(text, scale).height + 16;
    cv::Mat out(img.rows + band, img.cols, CV_8UC3, STAMP_BG);
    img.copyTo(out(cv::Rect(0, 0, img.cols, img.rows)));
    cv::line(out, cv::Point(0, img.rows), cv::Point(img.cols - 1, img.rows), STAMP_INK, 1);
    put(out, text, img.cols / 2, img.rows + band / 2 + 1, scale, 0, 0, STAMP_INK, 1);
    return out;
}

extern "C" int draw_stamp_png(const char *path, const char *text, char *err, size_t errlen)
{
    if (!check_path(path, err, errlen)) return -1;
    if (!text || !*text) {
        set_err(err, errlen, "%s: no stamp text", path);
        return -1;
    }
    int w = 0, h = 0;
    unsigned char *rgb = NULL;
    if (draw_read_rgb8(path, &w, &h, &rgb, err, errlen)) return -1;
    cv::Mat img(h, w, CV_8UC3);
    rgb_to_bgr(rgb, w, h, img);
    free(rgb);
    std::string t = ascii(text);
    return draw_png(path, err, errlen, [&]() { return stamped(img, t); });
}

