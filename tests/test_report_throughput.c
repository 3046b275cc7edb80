/* test_report_throughput.c - the throughput page (report_throughput.h) of rows made here by
 * hand, each figure of the expected page worked out by hand from the rows' rates (comments
 * give the arithmetic): the peak line, the default build options' table with its derived
 * columns (x pow(), x model ref, x tuned C, of peak, C G evals/s), the note of a C loop with no
 * ratio, the build options' table (x default, accuracy, a failed and a non-finite cell), the
 * accuracy sweep's line, the text form's columns, and the rows of two devices. No device. */
#include "check.h"
#include "mdbuf.h"
#include "rdoc.h"
#include "report_throughput.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static struct rd_row *result(struct rdoc *d, const char *device, const char *label, const char *variant,
                             const char *mode, double rate, double lo, double hi)
{
    struct rd_row *r = rdoc_row(d, device, label);
    rd_row_key(r, "label", NULL, label);
    rd_row_key(r, "variant", NULL, variant);
    rd_row_key(r, "n_mode", "n ", mode);
    rd_row_attr(r, "kind", strcmp(label, "pow") == 0 ? "builtin" : "model");
    struct rd_metric *m = rd_row_metric(d, r, "evals_per_s", "1/s", RD_HIGHER, 1, rate);
    m->lo = lo;
    m->hi = hi;
    return r;
}

static void peak(struct rdoc *d, const char *device, double flops, const char *failed)
{
    struct rd_row *r = rdoc_row(d, device, "peak");
    rd_row_key(r, "reference", NULL, "peak (reference kernel)");
    if (failed)
        rd_row_fail(r, "failed", failed);
    rd_row_metric(d, r, "flops_per_s", "FLOP/s", RD_HIGHER, 1, flops);
}

static void one_device_rows(struct rdoc *d)
{
    rdoc_text(d, "reps", "3");
    rdoc_text(d, "tuned_c_threads", "4");
    peak(d, "", 2e11, NULL);   /* 200 GFLOP/s = 100 G FMA/s */
    struct rd_row *r = result(d, "", "pow", "default", "uniform", 1e9, 0.9e9, 1.1e9);
    rd_row_metric(d, r, "host_c.evals_per_s", "1/s", RD_HIGHER, 1, 0.5e9);
    r = result(d, "", "phong", "default", "uniform", 2e9, 1.5e9, 2e9);
    rd_row_attr(r, "model_reference", "phong");
    rd_row_metric(d, r, "host_c.evals_per_s", "1/s", RD_HIGHER, 1, 4e9);
    r = result(d, "", "fq2", "default", "uniform", 30e9, 29e9, 31e9);
    rd_row_attr(r, "model_reference", "phong");
    rd_row_metric(d, r, "accuracy.max_diff_of_peak", "1", RD_NEITHER, 0, 9.3e-8);
    rd_row_text(d, r, "host_c_reason", "its sums differ from the device's");
    r = result(d, "", "fq2", "default", "varying", 20e9, 20e9, 20e9);
    rd_row_attr(r, "model_reference", "phong");
    rd_row_metric(d, r, "accuracy.max_diff_of_peak", "1", RD_NEITHER, 0, 9.3e-8);
    r = result(d, "", "pow", "fast-relaxed-math", "uniform", 1e9, 1e9, 1e9);
    rd_row_text(d, r, "note", "some values were NaN or Inf");
    r = result(d, "", "phong", "fast-relaxed-math", "uniform", NAN, NAN, NAN);
    rd_row_fail(r, "failed", "the build failed");
    r = result(d, "", "fq2", "fast-relaxed-math", "uniform", 45e9, 44e9, 46e9);
    rd_row_metric(d, r, "accuracy.max_diff_of_peak", "1", RD_NEITHER, 0, 2.5e-7);
    /* the sweep: fq2's 1000 points at 1e6 points/s on the device (1 ms) and 2.5e5 in C (4 ms) */
    rdoc_text(d, "sweep_grid", "n 2..1000 step 50, 16 samples per zone");
    r = rdoc_row(d, "", "fq2");
    rd_row_key(r, "label", NULL, "fq2");
    rd_row_key(r, "sweep", NULL, "accuracy sweep");
    rd_row_metric(d, r, "points", "1", RD_NEITHER, 0, 1000);
    rd_row_metric(d, r, "device_points_per_s", "1/s", RD_HIGHER, 1, 1e6);
    rd_row_metric(d, r, "host_c_points_per_s", "1/s", RD_HIGHER, 1, 2.5e5);
    r = rdoc_row(d, "", "phong");
    rd_row_key(r, "label", NULL, "phong");
    rd_row_key(r, "sweep", NULL, "accuracy sweep");
    rd_row_fail(r, "failed", "the C figures differ");
    rd_row_metric(d, r, "points", "1", RD_NEITHER, 0, 1000);
}

static char *page(const struct rdoc *d, int md)
{
    struct md_buf b;
    md_init(&b);
    CHECK(report_throughput_page(&b, d, md) == 0, "page drawn");
    return b.s;
}

static void check_markdown(void)
{
    CHECK_CASE("markdown");
    struct rdoc d;
    rdoc_init(&d, "brdfbench.throughput/5", "throughput", "throughput.json");
    one_device_rows(&d);
    char *p = page(&d, 1);
    static const char *const want[] = {
        "device peak: 200 GFLOP/s (float16 FMA chains) = 100 G FMA/s; fraction of peak = evaluations/s per FMA/s\n\n",
        "**G evaluations/s, default build options (median of 3 launches, profiling events; tuned C: 4 threads)**\n\n",
        "| model | n | G evals/s | min - max | x pow() | x model ref | x tuned C | of peak | C G evals/s |\n"
        "|---|---|---:|---:|---:|---:|---:|---:|---:|\n",
        /* pow: 1/1 = 1 x pow(); no reference; 1 / 0.5 = 2 x tuned C; 1 / 100 = 1% of peak */
        "| pow() built-in | uniform | 1 | 0.9 - 1.1 | 1 | - | 2 | 1% | 0.5 |\n",
        /* phong: 2 / 1 = 2; its own reference: 1; 2 / 4 = 0.5; 2 / 100 = 2% */
        "| phong | uniform | 2 | 1.5 - 2 | 2 | 1 | 0.5 | 2% | 4 |\n",
        /* fq2: 30 / 1 = 30; 30 / 2 = 15 x phong; no C rate; 30 / 100 = 30% */
        "| fq2 | uniform | 30 | 29 - 31 | 30 | 15 | - | 30% | - |\n",
        /* varying: neither pow() nor phong measured in that mode; 20 / 100 = 20% */
        "| fq2 | varying | 20 | 20 - 20 | - | - | - | 20% | - |\n",
        "- x tuned C, fq2 uniform: none: its sums differ from the device's\n\n",
        "**build options: G evaluations/s (x default) | max |device - double| / reference peak**\n\n",
        "| model | n | default | accuracy | fast-relaxed-math | accuracy |\n|---|---|---:|---:|---:|---:|\n",
        "| pow() built-in | uniform | 1 | - | !1 (1.00x) | - |\n",
        "| phong | uniform | 2 | - | failed | - |\n",
        /* 45 / 30 = 1.50 x default */
        "| fq2 | uniform | 30 | 9.3e-08 | 45 (1.50x) | 2.5e-07 |\n",
        "\n! some values were NaN or Inf under these build options (timed all the same)\n\n",
        /* 1 ms and 4 ms: 1000 / 1 ms = 0.001 G points/s, 1000 / 4 ms = 0.00025 G points/s, 4 / 1 */
        "accuracy sweep (n 2..1000 step 50, 16 samples per zone, 1 model, 1e+03 points): device 0.001 s "
        "(0.001 G points/s), tuned C 0.004 s (0.00025 G points/s): 4.00x\n",
    };
    /* the pieces in this order, one after the other, and nothing else */
    const char *at = p ? p : "";
    for (size_t i = 0; i < sizeof want / sizeof want[0]; ++i) {
        size_t n = strlen(want[i]);
        CHECK(strncmp(at, want[i], n) == 0, "piece %zu: want \"%s\", have \"%.200s\"", i, want[i], at);
        if (strncmp(at, want[i], n) != 0)
            break;
        at += n;
    }
    CHECK(*at == '\0', "nothing after the sweep line: \"%.200s\"", at);
    free(p);
    rdoc_free(&d);
}

/* The text form: the same figures in fixed-width columns, split here at the spaces. */
static void check_text(void)
{
    CHECK_CASE("text");
    struct rdoc d;
    rdoc_init(&d, "brdfbench.throughput/5", "throughput", "throughput.json");
    one_device_rows(&d);
    char *p = page(&d, 0);
    const char *line = p ? strstr(p, "\nphong ") : NULL;
    CHECK(line != NULL, "a line for phong");
    if (line) {
        char buf[256], *save = NULL;
        snprintf(buf, sizeof buf, "%.*s", (int)strcspn(line + 1, "\n"), line + 1);
        static const char *const cells[] = { "phong", "uniform", "2", "1.5", "-", "2", "2", "1", "0.5", "2%", "4" };
        size_t k = 0;
        for (char *t = strtok_r(buf, " ", &save); t; t = strtok_r(NULL, " ", &save), ++k)
            CHECK(k < sizeof cells / sizeof cells[0] && strcmp(t, cells[k]) == 0, "cell %zu: %s", k, t);
        CHECK(k == sizeof cells / sizeof cells[0], "%zu cells", k);
    }
    CHECK(p && strstr(p, "\n! x tuned C, fq2 uniform: none: its sums differ from the device's\n"), "the C note");
    CHECK(p && !strstr(p, "**") && !strstr(p, "|---"), "no markdown in the text form");
    free(p);
    rdoc_free(&d);
}

/* Rows of two devices: each device's tables in turn under its name, each with its own peak. */
static void check_devices(void)
{
    CHECK_CASE("devices");
    struct rdoc d;
    rdoc_init(&d, "brdfbench.throughput/5", "throughput", "throughput.json");
    rdoc_text(&d, "reps", "3");
    rdoc_text(&d, "tuned_c_threads", "4");
    peak(&d, "cpu A", 4e10, NULL);   /* 40 GFLOP/s = 20 G FMA/s */
    result(&d, "cpu A", "pow", "default", "uniform", 1e9, 1e9, 1e9);
    peak(&d, "gpu B", NAN, "the peak kernel failed");
    result(&d, "gpu B", "pow", "default", "uniform", 4e9, 4e9, 4e9);
    char *p = page(&d, 1);
    const char *a = p ? strstr(p, "**device: cpu A**\n\ndevice peak: 40 GFLOP/s") : NULL;
    const char *b = p ? strstr(p, "**device: gpu B**\n\ndevice peak: not measured (the peak kernel failed)") : NULL;
    CHECK(a && b && a < b, "each device under its name, in the rows' order: %s", p ? p : "(null)");
    /* 1 / 20 G FMA/s = 5% of A's peak; B's has none */
    CHECK(a && strstr(a, "| pow() built-in | uniform | 1 | 1 - 1 | 1 | - | - | 5% | - |\n"), "A's row");
    CHECK(b && strstr(b, "| pow() built-in | uniform | 4 | 4 - 4 | 1 | - | - | - | - |\n"), "B's row");
    free(p);
    rdoc_free(&d);
}

int main(void)
{
    check_markdown();
    check_text();
    check_devices();
    return check_summary();
}
