/* draw_compare.cpp - the verdict chart of brdfbench compare (draw.h): a panel per kind of row,
 * every row's ratios to the baseline and its verdict marks. */
#include "draw_common.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

using namespace draw_detail;

namespace {

const int LABEL_MAX = 420, LINE_H = 16, MARK_W = 18, BAR_H = 8;

cv::Scalar verdict_bgr(int v)
{
    switch (v) {
    case DRAW_VERDICT_BETTER: return cv::Scalar(60, 140, 0);
    case DRAW_VERDICT_WORSE: return cv::Scalar(0, 0, 200);
    case DRAW_VERDICT_SAME: return cv::Scalar(150, 150, 150);
    case DRAW_VERDICT_LOST: return cv::Scalar(0, 0, 0);
    case DRAW_VERDICT_UNDECIDED: return cv::Scalar(0, 160, 230);
    default: return WHITE;
    }
}

/* A text cut into lines of at most max_w pixels at `scale`: at " | " first, then at blanks, then
 * anywhere; a piece is never dropped. */
struct Wrapped {
    std::vector<std::string> lines;
    double scale;
};

/* The pieces of a label between its " | ", each but the last keeping its "|". */
std::vector<std::string> words_of(const std::string &t)
{
    std::vector<std::string> out = split_on(t, " | ");
    for (size_t i = 0; i + 1 < out.size(); i++) out[i] += " |";
    return out;
}

void break_piece(const std::string &piece, double scale, int max_w, std::vector<std::string> &lines)
{
    std::string cur;
    for (size_t i = 0; i < piece.size(); i++) {
        std::string next = cur + piece[i];
        if (!cur.empty() && text_size(next, scale).width > max_w) {
            size_t blank = cur.rfind(' ');
            if (blank != std::string::npos && blank > 0) {
                lines.push_back(cur.substr(0, blank));
                cur = cur.substr(blank + 1) + piece[i];
            } else {
                lines.push_back(cur);
                cur = std::string(1, piece[i]);
            }
        } else {
            cur = next;
        }
    }
    if (!cur.empty()) lines.push_back(cur);
}

Wrapped wrap(const char *text, int max_w)
{
    std::string t = ascii(text);
    Wrapped w{{}, S_TICK};
    while (w.scale > 0.38 && text_size(t, w.scale).width > max_w * 2) w.scale -= 0.02;   /* long: smaller */
    std::string cur;
    for (const std::string &piece : words_of(t)) {
        std::string next = cur.empty() ? piece : cur + " " + piece;
        if (text_size(next, w.scale).width <= max_w) {
            cur = next;
            continue;
        }
        if (!cur.empty()) w.lines.push_back(cur);
        cur.clear();
        if (text_size(piece, w.scale).width <= max_w) cur = piece;
        else break_piece(piece, w.scale, max_w, w.lines);
    }
    if (!cur.empty()) w.lines.push_back(cur);
    if (w.lines.empty()) w.lines.push_back("");
    return w;
}

void draw_mark(cv::Mat &img, int v, cv::Point c)
{
    cv::Scalar col = verdict_bgr(v);
    if (v == DRAW_VERDICT_BETTER || v == DRAW_VERDICT_WORSE) {
        int d = v == DRAW_VERDICT_BETTER ? -1 : 1;
        cv::Point tri[3] = {c + cv::Point(0, 5 * d), c + cv::Point(-6, -5 * d), c + cv::Point(6, -5 * d)};
        cv::fillConvexPoly(img, tri, 3, col, cv::LINE_8);
    } else if (v == DRAW_VERDICT_SAME) {
        cv::circle(img, c, 5, col, cv::FILLED, cv::LINE_8);
    } else if (v == DRAW_VERDICT_LOST) {
        cv::line(img, c + cv::Point(-5, -5), c + cv::Point(5, 5), col, 2, cv::LINE_8);
        cv::line(img, c + cv::Point(-5, 5), c + cv::Point(5, -5), col, 2, cv::LINE_8);
    } else if (v == DRAW_VERDICT_UNDECIDED) {
        cv::Point dia[4] = {c + cv::Point(0, -6), c + cv::Point(6, 0), c + cv::Point(0, 6), c + cv::Point(-6, 0)};
        cv::fillConvexPoly(img, dia, 4, col, cv::LINE_8);
    }
}

cv::Scalar series_bgr(int s) { return s == 0 ? cv::Scalar(60, 60, 60) : palette(s - 1); }

/* The ratio axis of a panel: logarithmic, through 1, around every finite positive ratio. */
Axis ratio_axis(const draw_verdict_panel &p, int S, int x0, int x1)
{
    double lo = 1, hi = 1;
    for (int i = 0; i < p.nrows * S; i++) {
        double r = p.ratio[i];
        if (std::isfinite(r) && r > 0) lo = std::min(lo, r), hi = std::max(hi, r);
    }
    lo = std::max(lo / 1.15, 1e-6);
    hi = std::min(hi * 1.15, 1e6);
    return Axis{lo, hi, true, (double)x0, (double)x1};
}

struct Layout {
    int W, label_x, label_w, plot_x, plot_w, mark_x, legend_h;
    std::vector<std::vector<Wrapped>> labels;   /* per panel, per row */
    std::vector<std::vector<int>> row_h;
};

int row_height(const Wrapped &w, int S) { return std::max((int)w.lines.size() * LINE_H + 6, S * (BAR_H + 2) + 8); }

/* The legend: a swatch per run (names wrapped), then the marks; returns its height. */
int draw_legend(cv::Mat *img, const struct draw_verdict_chart &c, int y0, int W)
{
    int x = 16, y = y0, line = 22;
    for (int s = 0; s < c.nseries; s++) {
        Wrapped w = wrap(c.series[s], W / 2);
        int tw = 0;
        for (auto &l : w.lines) tw = std::max(tw, text_size(l, w.scale).width);
        if (x > 16 && x + 40 + tw > W - 16) x = 16, y += line;
        if (img) {
            cv::rectangle(*img, cv::Rect(x, y + 4, 26, 12), series_bgr(s), cv::FILLED);
            for (size_t k = 0; k < w.lines.size(); k++) put(*img, w.lines[k], x + 32, y + 10 + (int)k * LINE_H, w.scale, -1, 0);
        }
        line = std::max(line, (int)w.lines.size() * LINE_H + 6);
        x += 50 + tw;
    }
    y += line + 4;
    static const int kinds[5] = {DRAW_VERDICT_BETTER, DRAW_VERDICT_WORSE, DRAW_VERDICT_SAME, DRAW_VERDICT_LOST,
                                 DRAW_VERDICT_UNDECIDED};
    static const char *names[5] = {"faster / better", "slower / worse", "same", "lost (missing or failed)",
                                   "undecided / noisy / changed"};
    x = 16;
    for (int k = 0; k < 5; k++) {
        int tw = text_size(names[k], S_TICK).width;
        if (x > 16 && x + 30 + tw > W - 16) x = 16, y += 22;
        if (img) {
            draw_mark(*img, kinds[k], cv::Point(x + 7, y + 10));
            put(*img, names[k], x + 20, y + 10, S_TICK, -1, 0);
        }
        x += 40 + tw;
    }
    return y + 26 - y0;
}

Layout layout(const struct draw_verdict_chart &c)
{
    Layout L;
    L.W = c.width > 0 ? c.width : 1100;
    int S = c.nseries, widest = 0;
    for (int k = 0; k < c.npanels; k++) {
        const draw_verdict_panel &p = c.panels[k];
        L.labels.emplace_back();
        L.row_h.emplace_back();
        for (int i = 0; i < p.nrows; i++) {
            Wrapped w = wrap(p.labels[i], LABEL_MAX);
            for (auto &l : w.lines) widest = std::max(widest, text_size(l, w.scale).width);
            L.row_h.back().push_back(row_height(w, S));
            L.labels.back().push_back(w);
        }
    }
    L.label_x = 16;
    L.label_w = widest;
    L.plot_x = L.label_x + widest + 14;
    L.W = std::max(L.W, L.plot_x + 300 + 70 + (S - 1) * MARK_W + 20);
    L.mark_x = L.W - 16 - (S - 1) * MARK_W;
    L.plot_w = L.mark_x - 70 - L.plot_x;
    L.legend_h = draw_legend(nullptr, c, 0, L.W);
    return L;
}

/* One panel from y; returns the y below it. */
int draw_panel_rows(cv::Mat &img, const struct draw_verdict_chart &c, const Layout &L, int k, int y)
{
    const draw_verdict_panel &p = c.panels[k];
    const int S = c.nseries;
    put(img, ascii(p.title), L.label_x, y + 4, S_LABEL, -1, -1, INK, 1);
    y += 30;
    int top = y, h = 0;
    for (int hh : L.row_h[k]) h += hh;
    Axis ax = ratio_axis(p, S, L.plot_x, L.plot_x + L.plot_w - 1);
    draw_x_ticks(img, ax, top + h, DRAW_FMT_PLAIN, 6, top);
    int x1 = (int)std::lround(ax.map(1.0));
    for (int yy = top; yy < top + h; yy += 8) cv::line(img, cv::Point(x1, yy), cv::Point(x1, std::min(yy + 4, top + h)), INK, 1);
    for (int i = 0; i < p.nrows; i++) {
        const Wrapped &w = L.labels[k][i];
        int rh = L.row_h[k][i];
        if (i % 2) cv::rectangle(img, cv::Rect(0, y, L.W, rh), cv::Scalar(246, 246, 246), cv::FILLED);
        int ly = y + (rh - (int)w.lines.size() * LINE_H) / 2 + LINE_H / 2;
        for (size_t l = 0; l < w.lines.size(); l++) put(img, w.lines[l], L.plot_x - 10, ly + (int)l * LINE_H, w.scale, 1, 0);
        int by = y + (rh - S * (BAR_H + 2)) / 2;
        for (int s = 0; s < S; s++, by += BAR_H + 2) {
            double r = p.ratio[i * S + s];
            if (std::isfinite(r) && r > 0) {
                int end = (int)std::lround(ax.map(std::min(std::max(r, ax.lo), ax.hi)));
                cv::rectangle(img, cv::Rect(L.plot_x, by, std::max(1, end - L.plot_x), BAR_H), series_bgr(s), cv::FILLED);
                char t[32];
                snprintf(t, sizeof t, "%.3gx", r);
                if (s > 0 || S == 1) put(img, t, end + 4, by + BAR_H / 2, 0.38, -1, 0);
            }
            if (s > 0) draw_mark(img, p.verdict[i * S + s], cv::Point(L.mark_x + (s - 1) * MARK_W + MARK_W / 2, by + BAR_H / 2));
        }
        y += rh;
    }
    cv::line(img, cv::Point(L.plot_x - 1, top), cv::Point(L.plot_x - 1, top + h), INK, 1);
    cv::line(img, cv::Point(L.plot_x - 1, top + h), cv::Point(L.plot_x + L.plot_w, top + h), INK, 1);
    return top + h + 40;
}

} /* namespace */

extern "C" void draw_verdict_rgb(int verdict, unsigned char rgb[3])
{
    cv::Scalar c = verdict_bgr(verdict);
    rgb[0] = (unsigned char)c[2];
    rgb[1] = (unsigned char)c[1];
    rgb[2] = (unsigned char)c[0];
}

extern "C" int draw_verdict_chart(const char *path, const struct draw_verdict_chart *c, char *err, size_t errlen)
{
    if (!check_path(path, err, errlen)) return -1;
    long rows = 0;
    for (int k = 0; c && c->panels && k < c->npanels; k++) {
        const draw_verdict_panel &p = c->panels[k];
        if (p.nrows < 1 || !p.labels || !p.ratio || !p.verdict) rows = -1e9;
        rows += p.nrows;
    }
    if (!c || c->nseries < 1 || !c->series || c->npanels < 1 || rows < 1 || rows * c->nseries > 20000) {
        set_err(err, errlen, "%s: a verdict chart needs 1..20000 bars in panels of labelled rows", path);
        return -1;
    }
    return draw_png(path, err, errlen, [&]() -> cv::Mat {
        Layout L = layout(*c);
        std::string t = ascii(c->title);
        int th = title_height(t), H = th + L.legend_h + 20;
        for (int k = 0; k < c->npanels; k++) {
            H += 30 + 40;
            for (int hh : L.row_h[k]) H += hh;
        }
        H += 30;
        if (H > 32000) throw std::runtime_error("the chart would be taller than 32000 pixels");
        cv::Mat img(H, L.W, CV_8UC3, WHITE);
        put_title(img, t);
        draw_legend(&img, *c, th, L.W);
        int y = th + L.legend_h + 10;
        for (int k = 0; k < c->npanels; k++) y = draw_panel_rows(img, *c, L, k, y);
        put(img, ascii(c->x_label), L.plot_x + L.plot_w / 2, y - 12, S_LABEL, 0, -1);
        return img;
    });
}
