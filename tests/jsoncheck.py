#!/usr/bin/env python3
"""jsoncheck.py - the shell tests' checks of the JSON (and CSV) files brdfbench writes, by name.

    python3 tests/jsoncheck.py CHECK FILE [ARGS...]

Runs the check function CHECK on FILE (and the further files or values in ARGS); exits 0 when
every assertion in it holds, else prints "FAIL CHECK FILE ARGS: what differed" (the assertion's
message and its line here) on stderr and exits 1. A check's expected values come from the test
(its arguments) or from a derivation written here, never from the program's output. JSON is
parsed strictly by load() (a NaN or Infinity literal fails it) unless a check says otherwise.
`python3 tests/jsoncheck.py --list` names the checks."""
import csv
import json
import math
import os
import sys
import traceback

CHECKS = {}


def check(fn):
    CHECKS[fn.__name__] = fn
    return fn


def no_const(x):
    raise ValueError("non-finite number in JSON: " + x)


def load(path, strict=True):
    with open(path) as f:
        return json.load(f, parse_constant=no_const) if strict else json.load(f)


def has_context(d, schema, keys):
    assert d["schema"] == schema, d["schema"]
    for k in keys:
        assert k in d["context"], k


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))


# ---- --device all: the gathered CSV (tests/test_device_csv.sh) -------------------------------

def device_tags(run):
    """The tag of each device of a --device all run folder, derived from the devices' own
    documents: the device's name, with " #k" (its place, from 1) where an earlier device of the
    list has the same name."""
    tags, names, k = [], [], 1
    while os.path.isdir(f"{run}/devices/{k}"):
        doc = [f for f in os.listdir(f"{run}/devices/{k}") if f.endswith(".json")]
        assert doc, f"{run}/devices/{k} holds no JSON document"
        name = load(f"{run}/devices/{k}/{sorted(doc)[0]}")["context"]["device"]
        tags.append(name + (" #%d" % k if name in names else ""))
        names.append(name)
        k += 1
    return tags


@check
def device_csv(gathered, run, name, ndevices):
    """GATHERED (RUN/NAME or a copy) is the header `device` + the devices' header, then each
    device's rows of RUN/devices/<k>/NAME in turn, each led by its tag, CSV-quoted (RFC 4180);
    RUN has NDEVICES devices with that many distinct tags."""
    tags = device_tags(run)
    assert len(tags) == int(ndevices) == len(set(tags)), (tags, ndevices)
    rows = read_csv(gathered)
    per = [read_csv(f"{run}/devices/{k + 1}/{name}") for k in range(len(tags))]
    for p in per:
        assert p[0] == per[0][0], ("the devices' headers differ", p[0], per[0][0])
    assert rows[0] == ["device"] + per[0][0], ("header", rows[0], per[0][0])
    expected = [[t] + r for t, p in zip(tags, per) for r in p[1:]]
    assert len(rows) - 1 == sum(len(p) - 1 for p in per), ("rows", len(rows) - 1, [len(p) - 1 for p in per])
    assert rows[1:] == expected, ("rows differ", rows[1:3], expected[:2])
    for t in tags:
        assert any(r[0] == t for r in rows[1:]), ("no row of", t)
    # the device column quoted in the text itself: "NAME" with each " doubled
    with open(gathered, newline="") as f:
        lines = f.read().split("\n")[1:]
    quoted = {'"' + t.replace('"', '""') + '",' for t in tags}
    for line in filter(None, lines):
        assert any(line.startswith(q) for q in quoted), ("device not quoted", line[:80])


@check
def csv_device_tags(path, *tags):
    """The first column of the CSV at PATH is `device`, and its values are TAGS, in that order
    of first appearance, each with the same number of rows."""
    rows = read_csv(path)
    assert rows[0][0] == "device", rows[0]
    seen = []
    for r in rows[1:]:
        if r[0] not in seen:
            seen.append(r[0])
    assert seen == list(tags), (seen, tags)
    counts = [sum(r[0] == t for r in rows[1:]) for t in tags]
    assert len(set(counts)) == 1 and counts[0] > 0, counts


# ---- JSON Schemas (tests/test_machine_readable.sh) -------------------------------------------

def schema_validators(folder):
    """Every docs/schemas/*.schema.json, checked as a draft 2020-12 schema, by its schema string."""
    import glob
    import jsonschema   # python3-jsonschema (scripts/setup.sh)
    out = {}
    for f in sorted(glob.glob(folder + "/*.schema.json")):
        sch = load(f)
        jsonschema.Draft202012Validator.check_schema(sch)
        kind = sch["properties"]["schema"]["const"]
        assert os.path.basename(f) == kind.replace("/", "-") + ".schema.json", (f, kind, "file not named after its kind")
        out[kind] = jsonschema.Draft202012Validator(sch)
    return out


@check
def schema_docs(folder, *docs):
    """Each document DOCS validates against the schema of FOLDER its "schema" string names."""
    schemas = schema_validators(folder)
    assert docs, "no document given"
    for n in docs:
        d = load(n)
        assert d["schema"] in schemas, (n, d["schema"], "no schema file")
        e = list(schemas[d["schema"]].iter_errors(d))
        assert not e, (n, [(x.json_path, x.message[:200]) for x in e[:3]])


def broken_copies(t):
    """(what, document) pairs, each a document of folder T with one thing broken."""
    import copy
    docs = {}

    def b(name):
        if name not in docs:
            docs[name] = load(f"{t}/{name}.json")
        return copy.deepcopy(docs[name])
    out = []

    def add(what, d):
        out.append((what, d))
    d = b("acc"); d["results"][0]["epicentre"]["at_x"] = 3.2; add("x > pi/2", d)
    d = b("acc"); del d["results"][0]["whole"]; add("no whole", d)
    d = b("frontier"); d["models"][0]["on_front"] = "yes"; add("on_front a string", d)
    d = b("throughput"); d["results"][0]["evals_per_s"]["median"] = -1; add("negative rate", d)
    d = b("render"); del d["scenes"]; add("no scenes", d)
    d = b("reproduce"); d["claims"] = []; add("no claims", d)
    d = b("compare"); d["rows"][0]["sense"] = "faster"; add("bad sense", d)
    d = b("list"); d["schema"] = "brdfbench.list/2"; add("wrong version", d)
    d = b("fit"); d["status"] = "maybe"; add("fit: status not in its enum", d)
    d = b("fit"); assert d["max_abs_cap"] is None; del d["max_abs_cap_reason"]; add("fit: a null cap without its reason", d)
    d = b("fit"); d["compare"][0]["epicentre"]["at_x"] = 3.2; add("fit: x > pi/2", d)
    d = b("fitfam"); del d["fit"]; add("fit_family: no fit", d)
    d = b("fitfam"); d["objective"] = "speed"; add("fit_family: objective not in its enum", d)
    d = b("gate"); d["gates"][0]["status"] = "passed"; add("gate: status not in its enum", d)
    d = b("gate"); d["gates"][0]["measured"] = None; d["gates"][0].pop("reason", None); add("gate: null measured without a reason", d)
    d = b("gates"); del d["gates"][0]["max"]; d["gates"][0].pop("min", None); add("gates: a gate without a bound", d)
    d = b("q_sweep"); d["Q"][0] = 1.5; add("q_sweep: Q past 1", d)
    d = b("energy"); d["albedo"]["models"][0]["energy_conserving"] = "no"; add("energy: a boolean made a string", d)
    d = b("physical"); d["cost"]["rows"][0]["evaluations_per_s"] = -1; add("physical: negative rate", d)
    d = b("physical"); d["cost"]["rows"][0]["status"] = "fine"; add("physical: status not in its enum", d)
    d = b("measured"); d["materials"][0]["cells"] = 1000; add("measured: not a MERL table's cells", d)
    d = b("measured"); d["materials"][0]["blinn_phong"]["status"] = "done"; add("measured: fit status not in its enum", d)
    d = b("field"); d["epicentre_max_rel"]["x"] = 3.2; add("field: x > pi/2", d)
    d = b("field"); del d["attenuation_abs"]; add("field: no attenuation_abs", d)
    d = b("plots"); d["figures"][0]["kind"] = "pie"; add("plots: kind not in its enum", d)
    d = b("plots"); d["figures"] = []; add("plots: no figures", d)
    return out


@check
def schema_broken(folder, t):
    """Every broken copy (broken_copies) of a document of folder T fails its schema (or names
    none)."""
    schemas = schema_validators(folder)
    for what, d in broken_copies(t):
        bad = d["schema"] not in schemas or list(schemas[d["schema"]].iter_errors(d))
        assert bad, ("a broken document validates", what)


@check
def schemas_cover(schemas_h, folder):
    """Every schema string of host/output/schemas.h has its file in FOLDER, but the older
    versions kept only for the readers (a macro named *_SCHEMA_V<k>); and every file there is of
    a string schemas.h defines."""
    import re
    defs = re.findall(r'^#define (\w+) "(brdfbench\.[a-z_]+/[0-9]+)"', open(schemas_h).read(), re.M)
    assert len(defs) >= 17, ("too few schema strings found in schemas.h", defs)
    files = set(os.listdir(folder))
    current = {v for k, v in defs if not re.search(r"_V[0-9]+$", k)}
    for v in sorted(current):
        assert v.replace("/", "-") + ".schema.json" in files, (v, "has no schema file in", folder)
    kinds = {f[: -len(".schema.json")].replace("-", "/") for f in files if f.endswith(".schema.json")}
    assert kinds <= current, ("schema files of no current kind", sorted(kinds - current))


# ---- test_render_cli.sh ------------------------------------------------------------------------

@check
def render_cli_render_contract(*args):
    """check_json of test_render_cli.sh: render.json contract"""
    argv = ["check_json", *args]
    d = load(argv[1])
    import os
    has_context(d, "brdfbench.render/1", ("date", "device", "platform_version", "build_options", "git_revision"))
    scenes = {s["scene"]: s for s in d["scenes"]}
    assert sorted(scenes) == ["spheres", "teapot"], sorted(scenes)
    for s in scenes.values():
        assert [m["model"] for m in s["models"]] == ["phong", "blinn", "cq2", "fq2"]
        for m in s["models"]:
            assert m["double_reference_check"]["within_bound"] is True, m
            for f in m["files"].values():
                assert os.path.getsize(os.path.join(argv[2], f)) > 0, f
            # a model that is its own reference has no error at all
            if m["model"] == m["reference"]:
                assert m["metrics"]["max_abs"] == 0 and m["metrics"]["psnr_db"] is None
        (t,) = s["timings"]
        assert (t["width"], t["height"]) == (128, 64)
        cp = t["copy"]
        assert abs(cp["mpixel_per_s"] - 128 * 64 / (cp["median_ms"] * 1e3)) <= 1e-9 * cp["mpixel_per_s"], cp
        names = {e["name"]: e for e in t["entries"]}
        assert set(names) == {"phong", "blinn", "cq2", "fq2"}, names
        for e in names.values():
            assert 0 < e["min_ms"] <= e["median_ms"] <= e["max_ms"], e
            # Mpixel/s is the image's pixels over the median time (128 x 64 here)
            assert abs(e["mpixel_per_s"] - 128 * 64 / (e["median_ms"] * 1e3)) <= 1e-9 * e["mpixel_per_s"], e
            # each of the --reps 3 timed launches' rate: the slowest is the longest time, the
            # middle one is the median's
            reps = sorted(e["mpixel_per_s_reps"])
            assert len(reps) == 3, e
            assert abs(reps[0] - 128 * 64 / (e["max_ms"] * 1e3)) <= 1e-9 * reps[0], e
            assert abs(reps[1] - e["mpixel_per_s"]) <= 1e-9 * reps[1], e
            assert abs(reps[2] - 128 * 64 / (e["min_ms"] * 1e3)) <= 1e-9 * reps[2], e
            # the ratio is the interleaved copy's median over this entry's median
            assert abs(e["fraction_of_copy"] - e["copy_median_ms_interleaved"] / e["median_ms"]) < 1e-9
            # the speed-up is the reference's median time over this entry's (docs/definitions.md: cq2 and fq2 against
            # phong; a reference entry has none other than itself)
            r = names[e["reference"]]
            assert abs(e["speedup_vs_reference"] - r["median_ms"] / e["median_ms"]) <= 1e-9 * e["speedup_vs_reference"], e
        assert names["cq2"]["reference"] == "phong" and names["fq2"]["reference"] == "phong"
        assert names["blinn"]["reference"] == "blinn"


def main(argv):
    if len(argv) == 2 and argv[1] == "--list":
        print("\n".join(sorted(CHECKS)))
        return 0
    if len(argv) < 3 or argv[1] not in CHECKS:
        print("usage: jsoncheck.py CHECK FILE [ARGS...]; checks: " + ", ".join(sorted(CHECKS)), file=sys.stderr)
        return 2
    if not __debug__:
        print("jsoncheck.py: run without -O (its checks are assertions)", file=sys.stderr)
        return 2
    name, args = argv[1], argv[2:]
    try:
        CHECKS[name](*args)
    except SystemExit as e:   # a check that ends itself: sys.exit(0) holds, any other code fails
        if e.code in (None, 0):
            return 0
        print(f"FAIL {name} {' '.join(args)}: exit {e.code}"[:2000], file=sys.stderr)
        return 1
    except Exception as e:   # an assertion, or a member or file the check needs that is missing
        here = [f for f in traceback.extract_tb(e.__traceback__) if f.filename == __file__]
        where = here[-1]
        what = f"{type(e).__name__}: {e}" if not isinstance(e, AssertionError) else (str(e) or "assertion")
        print(f"FAIL {name} {' '.join(args)}: {what} (jsoncheck.py:{where.lineno}: {where.line})"[:2000],
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
