/* draw_common.hpp - what the pictures of draw_image.cpp, draw_plot.cpp, draw_chart.cpp and
 * draw_compare.cpp share, defined in draw.cpp: text in the Hershey font, titles, colour maps, axes and ticks, colour bars,
 * the quick-run stamp and the atomic PNG write. C++ only; nothing outside host/output includes it.
 */
#ifndef BRDF_DRAW_COMMON_HPP
#define BRDF_DRAW_COMMON_HPP

#include "draw.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <exception>
#include <string>
#include <vector>

namespace draw_detail {

const cv::Scalar INK(40, 40, 40);          /* text and axes (BGR) */
const cv::Scalar GRID(225, 225, 225);
const cv::Scalar WHITE(255, 255, 255);
const cv::Scalar NODATA(100, 90, 90);      /* NaN cells / background pixels: RGB (90, 90, 100), a
                                              bluish grey no anti-aliased text pixel takes */
const cv::Scalar STAMP_BG(200, 240, 255);   /* the quick-run stamp's band: RGB (255, 240, 200) */
const cv::Scalar STAMP_INK(20, 20, 160);    /* and its text: RGB (160, 20, 20) */
const int FONT = cv::FONT_HERSHEY_SIMPLEX;
const double S_TICK = 0.5, S_LABEL = 0.58, S_TITLE = 0.72;


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


void set_err(char *err, size_t errlen, const char *fmt, ...);
cv::Scalar palette(int i);
std::string ascii(const char *s);
std::vector<std::string> split_on(const std::string &s, const std::string &sep);
std::vector<std::string> split_lines(const std::string &s);
cv::Size text_size(const std::string &t, double scale, int *baseline = nullptr);
void put(cv::Mat &img, const std::string &t, int x, int y, double scale, int halign, int valign,
         cv::Scalar colour = INK, int thickness = 1);
void put_vertical(cv::Mat &img, const std::string &t, int cx, int cy, double scale);
int title_height(const std::string &title);
void put_title(cv::Mat &img, const std::string &title);
cv::Vec3b cmap_bgr(int cmap, int index);
int value_index(double v, double vmin, double vmax);
double nice_step(double raw);
std::vector<double> linear_ticks(double lo, double hi, int target, double *step_out);
std::vector<double> log_ticks(double lo, double hi);
std::string tick_label(double v, double step, int format);
void draw_x_ticks(cv::Mat &img, const Axis &a, int y, int format, int target, int grid_top = -1);
int draw_y_ticks(cv::Mat &img, const Axis &a, int x, int format, int target, int grid_right = -1);
int y_label_width(const Axis &a, int format, int target);
void draw_colour_bar(cv::Mat &img, cv::Rect r, int cmap, double vmin, double vmax, int format,
                     const std::string &caption);
int colour_bar_extent(double vmin, double vmax, int format, int bar_w);
void colour_scale(double vmin, double vmax, double data_max, double *lo, double *hi);
int write_png(const char *path, const cv::Mat &bgr, char *err, size_t errlen);
bool check_path(const char *path, char *err, size_t errlen);
void draw_error_bar(cv::Mat &img, int a, int b, int cy, int tick);
void rgb_to_bgr(const unsigned char *rgb, int w, int h, cv::Mat dst);


/* The image that draw() makes, written to path as PNG; an OpenCV exception on the way becomes
 * the error "path: what", -1. */
template <class Draw> int draw_png(const char *path, char *err, size_t errlen, Draw draw)
{
    try {
        cv::Mat img = draw();
        return write_png(path, img, err, errlen);
    } catch (const std::exception &e) {
        set_err(err, errlen, "%s: %s", path, e.what());
        return -1;
    }
}

} /* namespace draw_detail */

#endif /* BRDF_DRAW_COMMON_HPP */
