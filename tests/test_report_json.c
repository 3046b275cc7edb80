/* test_report_json.c - the strict JSON reader behind `brdfbench plot`/`heatmap`: values read
 * as written (worked by hand from the RFC 8259 grammar), and every kind of malformed input
 * refused with the line and column of the problem; and the writer (jsonw.c), which refuses to
 * write an unbalanced document. No device needed. */
#include "check.h"
#include "jsonr.h"
#include "jsonw.h"

#include <unistd.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int parse(const char *text, struct jr_doc *d, char *err, size_t errlen)
{
    return jr_parse_text(text, strlen(text), "t.json", d, err, errlen);
}

static void test_values(void)
{
    struct jr_doc d;
    char err[512] = "";
    const char *text = "{\n  \"a\": [1, -2.5e3, 0.125, null, true, false],\n  \"s\": \"x\\n\\u00e9\\ud83d\\ude00\\\"\",\n"
                       "  \"o\": {\"k\": {}}, \"e\": []\n}";
    CHECK(parse(text, &d, err, sizeof err) == 0, "valid document: %s", err);
    const struct jr_value *a = jr_get(&d.root, "a");
    CHECK(a && a->type == JR_ARR && a->count == 6, "array of 6");
    if (a && a->count == 6) {
        CHECK(a->items[0].num == 1 && a->items[1].num == -2500 && a->items[2].num == 0.125, "numbers");
        CHECK(a->items[3].type == JR_NULL && a->items[4].num == 1 && a->items[5].num == 0, "null, true, false");
        CHECK(a->line == 2 && a->col == 8, "array starts at 2:8 (got %d:%d)", a->line, a->col);
    }
    const char *s = NULL;
    CHECK(jr_need_str(&d, &d.root, "s", &s, err, sizeof err) == 0, "string member");
    /* "x", newline, U+00E9 (C3 A9), U+1F600 from its surrogate pair (F0 9F 98 80), quote */
    CHECK(s && strcmp(s, "x\n\xc3\xa9\xf0\x9f\x98\x80\"") == 0, "escapes decoded");
    double *nums = NULL;
    size_t n = 0;
    CHECK(jr_need_num_array(&d, &d.root, "a", &nums, &n, err, sizeof err) == 2, "booleans are not numbers");
    CHECK(strstr(err, "t.json:2:") && strstr(err, "item 4"), "message names item and line: %s", err);
    double v;
    CHECK(jr_need_num(&d, &d.root, "missing", &v, err, sizeof err) == 2 && strstr(err, "\"missing\" is missing"),
          "missing member: %s", err);
    CHECK(jr_need_num(&d, &d.root, "s", &v, err, sizeof err) == 2 && strstr(err, "t.json:3:8") &&
              strstr(err, "a string, a number expected"),
          "wrong type at its position: %s", err);
    jr_free(&d);
    CHECK(parse("[1, null]", &d, err, sizeof err) == 0, "top-level array");
    jr_free(&d);
    CHECK(parse("{\"v\": null}", &d, err, sizeof err) == 0 && jr_need_num(&d, &d.root, "v", &v, err, sizeof err) == 0 &&
              isnan(v),
          "null number reads as NaN");
    jr_free(&d);
}

static void test_errors(void)
{
    static const struct {
        const char *text, *where, *what;
    } cases[] = {
        /* Where: the line and column (1-based, counted by hand in the text) of the token at
         * fault; what: the reason in libjansson's words (a trailing comma is named as such). */
        {"{\"a\": 1,}", "1:9", "trailing comma"},
        {"[1, 2,]", "1:7", "trailing comma"},
        {"{\"a\": 01}", "1:7", "invalid token near '0'"},
        {"{\"a\": NaN}", "1:7", "invalid token near 'NaN'"},
        {"{\"a\": 1e999}", "1:7", "real number overflow"},
        {"{'a': 1}", "1:2", "string or '}' expected"},
        {"{\"a\" 1}", "1:6", "':' expected"},
        {"{\"a\": 1, \"a\": 2}", "1:10", "duplicate object key"},
        {"{\"b\": {\"a\": 1, \"a\": 2}}", "1:16", "duplicate object key"},
        {"{\"a\": \"x\ty\"}", "1:7", "control character 0x9"},
        {"{\"a\": \"\\q\"}", "1:7", "invalid escape"},
        {"{\"a\": \"\\ud800x\"}", "1:7", "invalid Unicode '\\uD800'"},
        {"{\"a\": \"\\u0000\"}", "1:7", "\\u0000 is not allowed"},
        {"{\"a\": 1} x", "1:10", "end of file expected"},
        {"// c\n{}", "1:1", "invalid token near '/'"},
        {"{\"a\": [1, 2}", "1:12", "']' expected"},
        {"{\"a\": tru}", "1:7", "invalid token near 'tru'"},
        {"{\n\n  \"a\": \"open", "3:8", "unexpected end of file: premature end of input"},
        {"{\"a\": [1, 2", "1:12", "unexpected end of file: ']' expected"},
        {"", "1:1", "unexpected token near end of file"},
        {"{\"a\": -}", "1:7", "invalid token near '-'"},
        {"{\"a\": 1.}", "1:7", "invalid token near '1.'"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct jr_doc d;
        char err[512] = "", where[32];
        snprintf(where, sizeof where, "t.json:%s:", cases[i].where);
        int rc = parse(cases[i].text, &d, err, sizeof err);
        CHECK(rc == 2 && strstr(err, where) && strstr(err, cases[i].what), "case %zu (%s): got rc %d, '%s', want %s %s",
              i, cases[i].text, rc, err, where, cases[i].what);
        if (rc == 0) jr_free(&d);
    }
    /* deep nesting is refused, not a stack overflow */
    char deep[400];
    memset(deep, '[', sizeof deep - 1);
    deep[sizeof deep - 1] = 0;
    struct jr_doc d;
    char err[512];
    CHECK(parse(deep, &d, err, sizeof err) == 2 && strstr(err, "nesting"), "deep nesting: %s", err);
    CHECK(jr_parse_file("/nonexistent-brdfbench/x.json", &d, err, sizeof err) == 2 &&
              strstr(err, "/nonexistent-brdfbench/x.json"),
          "missing file named: %s", err);
}

/* A writer that leaves a container open, closes one twice or closes the other kind is refused,
 * and nothing is written; a balanced one is written and reads back. */
static void test_writer_balance(void)
{
    char dir[] = "/tmp/brdf_jw_XXXXXX", path[256], err[512];
    CHECK(mkdtemp(dir) != NULL, "temporary folder");
    snprintf(path, sizeof path, "%s/doc.json", dir);
    for (int c = 0; c < 4; ++c) {
        struct jw w;
        jw_init(&w);
        jw_obj_begin(&w);
        jw_kv_arr(&w, "a");
        jw_num(&w, 1);
        if (c != 1) jw_arr_end(&w);        /* case 1: the array left open */
        if (c == 3) jw_arr_end(&w);        /* case 3: an array closed that is not open */
        if (c != 2) jw_obj_end(&w);        /* case 2: the object left open */
        else jw_arr_end(&w);               /* ... and closed as an array */
        err[0] = '\0';
        int rc = jw_write_file_free(&w, path, err, sizeof err);
        if (c == 0) {
            CHECK(rc == 0, "balanced document written: %s", err);
            struct jr_doc d;
            CHECK(jr_parse_file(path, &d, err, sizeof err) == 0, "and read back: %s", err);
            jr_free(&d);
            unlink(path);
        } else {
            CHECK(rc == -1 && strstr(err, "unbalanced"), "case %d refused (%s)", c, err);
            CHECK(access(path, F_OK) != 0, "case %d: nothing written", c);
        }
    }
    rmdir(dir);
}

int main(void)
{
    test_values();
    test_errors();
    test_writer_balance();
    return check_summary();
}
