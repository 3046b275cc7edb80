/* draw_chart.cpp - the scatter plots (frontier, measured) of draw.h. */
#include "draw_common.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace draw_detail;

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
