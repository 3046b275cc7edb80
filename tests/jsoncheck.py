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


# Broken copies: (document, what is broken, edits). An edit is ("set", PATH, VALUE), ("del",
# PATH) (the member must be there), ("pop", PATH) (taken out if there) or ("none", PATH) (the
# member must be null already: the copy then tests a null without its reason).
BROKEN = [
    ("acc", "x > pi/2", [("set", ["results", 0, "epicentre", "at_x"], 3.2)]),
    ("acc", "no whole", [("del", ["results", 0, "whole"])]),
    ("frontier", "on_front a string", [("set", ["models", 0, "on_front"], "yes")]),
    ("throughput", "negative rate", [("set", ["results", 0, "evals_per_s", "median"], -1)]),
    ("render", "no scenes", [("del", ["scenes"])]),
    ("reproduce", "no claims", [("set", ["claims"], [])]),
    ("compare", "bad sense", [("set", ["rows", 0, "sense"], "faster")]),
    ("list", "wrong version", [("set", ["schema"], "brdfbench.list/2")]),
    ("fit", "status not in its enum", [("set", ["status"], "maybe")]),
    ("fit", "a null cap without its reason", [("none", ["max_abs_cap"]), ("del", ["max_abs_cap_reason"])]),
    ("fit", "x > pi/2", [("set", ["compare", 0, "epicentre", "at_x"], 3.2)]),
    ("fitfam", "no fit", [("del", ["fit"])]),
    ("fitfam", "objective not in its enum", [("set", ["objective"], "speed")]),
    ("gate", "status not in its enum", [("set", ["gates", 0, "status"], "passed")]),
    ("gate", "a null measured without a reason", [("set", ["gates", 0, "measured"], None), ("pop", ["gates", 0, "reason"])]),
    ("gates", "a gate without a bound", [("del", ["gates", 0, "max"]), ("pop", ["gates", 0, "min"])]),
    ("q_sweep", "Q past 1", [("set", ["Q", 0], 1.5)]),
    ("energy", "a boolean made a string", [("set", ["albedo", "models", 0, "energy_conserving"], "no")]),
    ("energy", "no reciprocity", [("del", ["reciprocity"])]),
    ("physical", "negative rate", [("set", ["cost", "rows", 0, "evaluations_per_s"], -1)]),
    ("physical", "status not in its enum", [("set", ["cost", "rows", 0, "status"], "fine")]),
    ("measured", "not a MERL table's cells", [("set", ["materials", 0, "cells"], 1000)]),
    ("measured", "fit status not in its enum", [("set", ["materials", 0, "blinn_phong", "status"], "done")]),
    ("field", "x > pi/2", [("set", ["epicentre_max_rel", "x"], 3.2)]),
    ("field", "no attenuation_abs", [("del", ["attenuation_abs"])]),
    ("plots", "kind not in its enum", [("set", ["figures", 0, "kind"], "pie")]),
    ("plots", "no figures", [("set", ["figures"], [])]),
]


def broken_copy(d, edits):
    import copy
    d = copy.deepcopy(d)
    for op, path, *value in edits:
        parent = d
        for k in path[:-1]:
            parent = parent[k]
        last = path[-1]
        if op == "set":
            parent[last] = value[0]
        elif op == "del":
            del parent[last]
        elif op == "pop":
            parent.pop(last, None)
        else:
            assert parent[last] is None, (path, parent[last], "expected null")
    return d


@check
def schema_broken(folder, t, *names):
    """Every broken copy (BROKEN) of the documents NAMES (T/NAME.json; all of BROKEN's without
    NAMES) fails its schema (or names none)."""
    schemas = schema_validators(folder)
    names = names or sorted({n for n, _, _ in BROKEN})
    for n in names:
        entries = [(what, edits) for m, what, edits in BROKEN if m == n]
        assert entries, (n, "has no broken copies in BROKEN")
        d = load(f"{t}/{n}.json")
        for what, edits in entries:
            b = broken_copy(d, edits)
            bad = b["schema"] not in schemas or list(schemas[b["schema"]].iter_errors(b))
            assert bad, ("a broken document validates", n, what)


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
    import os
    argv = ["check_json", *args]
    d = load(argv[1])
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


# ---- test_accuracy_pictures.sh -----------------------------------------------------------------

@check
def accuracy_pictures_z_beside_fq2(*args):
    """check_json of test_accuracy_pictures.sh: z is measured beside fq2"""
    argv = ["check_json", *args]
    d = load(argv[1])
    labels = [x["label"] for x in d["results"]]
    assert labels == ["fq2", "z"], labels
    z = d["results"][1]
    assert abs(z["epicentre"]["max_rel"] - 0.5) < 1e-12, z["epicentre"]


@check
def accuracy_pictures_field_z_closed_form(*args):
    """check_json of test_accuracy_pictures.sh: the field of z = 0.5 c^n has its closed-form peaks"""
    argv = ["check_json", *args]
    d = load(argv[1])
    assert d["model"] == "z" and d["reference"] == "phong", (d["model"], d["reference"])
    assert d["formula"] == "0.5*pow(c, n)" and d["lobe"] == "psi", (d["formula"], d["lobe"])
    assert abs(d["epicentre_max_rel"]["value"] - 0.5) < 1e-6, d["epicentre_max_rel"]
    assert abs(d["attenuation_max_abs"]["value"] - 0.5 * math.exp(-0.511)) < 1e-6, d["attenuation_max_abs"]
    assert d["grid"]["n_min"] == 2 and d["grid"]["n_max"] == 50, d["grid"]


@check
def accuracy_pictures_both_models_both_plots(*args):
    """check_json of test_accuracy_pictures.sh: both models in both plots"""
    argv = ["check_json", *args]
    d = load(argv[1])
    figs = {f["file"]: f for f in d["figures"]}
    for name in ("max_rel_error_epicentre_vs_n.png", "max_abs_error_vs_n.png"):
        labels = [s["label"] for s in figs[name]["series"]]
        assert "z" in labels and "fq2" in labels, (name, labels)
    z = [s for s in figs["max_rel_error_epicentre_vs_n.png"]["series"] if s["label"] == "z"][0]
    assert all(abs(v - 0.5) < 1e-6 for v in z["y"]), z["y"][:5]   # per-n figures plotted in float


# ---- test_report_cli.sh ------------------------------------------------------------------------

@check
def report_cli_frontier_all_models(*args):
    """check_json of test_report_cli.sh: the frontier of all --models"""
    argv = ["check_json", *args]
    d = load(argv[1])
    assert [m["model"] for m in d["models"]] == ["phong", "fvol", "cq2", "fq:Q=0.64"], [m["model"] for m in d["models"]]


# ---- test_measured_cli.sh ----------------------------------------------------------------------

@check
def measured_cli_measured(*args):
    """check_json of test_measured_cli.sh: measured.json"""
    argv = ["check_json", *args]
    d = load(argv[1])
    has_context(d, "brdfbench.measured/1", ["date", "device", "git_revision", "grid"])
    m = d["materials"][0]
    assert m["name"] == "blinn64", m["name"]
    assert m["unmeasured_cells"] == 32400 and m["negative_cells_rgb"] == [0, 32400, 0], m["negative_cells_rgb"]
    assert m["used_cells"] + m["below_horizon_cells"] + m["unmeasured_cells"] == 1458000
    assert m["fit_cells"] <= 5000
    bp = m["blinn_phong"]
    for key, want in (("n", 64), ("ks", 2.5), ("kd", 0.08)):
        assert abs(bp[key] / want - 1) < 1e-3, (key, bp[key])
    # the material is the Blinn-Phong lobe: each lobe's error against it is its error against the fit
    for l in m["lobes"]:
        assert abs(l["err_measured"] - l["err_phong"]) <= 1e-9 * max(l["err_phong"], 1e-300), l
    assert m["device_check"]["status"] == "ok", m["device_check"]
    assert len(m["slices"]["theta_d"]) == 3 and len(m["slices"]["theta_h_deg"]) == 90


# ---- test_device_check.sh ----------------------------------------------------------------------

@check
def device_check_user_model_at_large_n(*args):
    """test_device_check.sh: user model at large n: the polished maxima miss the brute force"""
    import csv, math, sys
    argv = ["-", *args]
    rows = list(csv.DictReader(open(argv[1])))
    assert len(rows) == 2, rows
    for row in rows:
        n = float(row["n"]); se = -math.expm1(-0.511 / n); k = float.fromhex("0x1.cac084p-2") * n   # 0.448f
        best = max(abs(max(1 - k * s, 0) ** 2 - math.exp(n * math.log1p(-s))) / math.exp(n * math.log1p(-s))
                   for s in (se * i / 200000 for i in range(200001)))
        got, x = float(row["epicentre_max_rel_fraction"]), float(row["epicentre_at_x_rad"])
        unit = 10 ** (math.floor(math.log10(best)) - 3)
        print(n, got, best, x, 2 * math.asin(math.sqrt(se / 2)))
        assert abs(got - best) <= 0.1 * unit, (n, got, best)
        assert x <= 2 * math.asin(math.sqrt(se / 2)) * (1 + 1e-12), (n, x)


# ---- test_frontier_cli.sh ----------------------------------------------------------------------

@check
def frontier_cli_fit_contract_or_fit_worse(*args):
    """test_frontier_cli.sh: fit.json contract, or the fit is worse than pow4fit"""
    import json, sys
    argv = ["-", *args]
    t = argv[1]
    def no_const(x): raise ValueError("non-finite number in JSON: " + x)
    f = json.load(open(t + "/fit/fit.json"), parse_constant=no_const)
    assert f["schema"] == "brdfbench.fit_family/1"
    assert f["family"] == "pow4" and f["objective"] == "max_rel"
    assert f["fit"]["status"] == "ok"
    assert f["model"].startswith("pow4:a=")
    a = json.load(open(t + "/acc/accuracy.json"), parse_constant=no_const)
    frozen = [r for r in a["results"] if r["model"] == "pow4fit"][0]["epicentre"]["max_rel"]
    assert f["fit"]["max_rel"] <= frozen * (1 + 1e-3), (f["fit"]["max_rel"], frozen)
    assert f["device"]["max_rel"] <= frozen * (1 + 1e-3), (f["device"]["max_rel"], frozen)
    # the trade-off runs from the least max delta to the least max Delta
    assert f["min_max_abs"]["max_abs"] <= f["min_max_rel"]["max_abs"]
    assert f["min_max_rel"]["max_rel"] <= f["min_max_abs"]["max_rel"]


@check
def frontier_cli_frontier_contract_bounds(*args):
    """test_frontier_cli.sh: frontier.json contract and bounds"""
    import json, sys
    argv = ["-", *args]
    d = argv[1]
    def no_const(x): raise ValueError("non-finite number in JSON: " + x)
    j = json.load(open(d + "/frontier.json"), parse_constant=no_const)
    assert j["schema"] == "brdfbench.frontier/1"
    for k in ("date", "device", "git_revision"):
        assert k in j["context"], k
    m = {r["model"]: r for r in j["models"]}
    assert set(m) == {"phong", "fq2", "pow4fit"}
    p4, fq2 = m["pow4fit"]["n_2_1000"], m["fq2"]["n_2_1000"]
    assert p4["max_rel"] <= 0.0060 and p4["max_abs"] <= 0.075, p4
    assert p4["max_rel"] < fq2["max_rel"] and p4["max_abs"] < fq2["max_abs"], (p4, fq2)
    assert m["phong"]["on_front"] is True
    assert m["phong"]["kind"] == "reference" and m["fq2"]["kind"] == "paper" and m["pow4fit"]["kind"] == "tuned"
    for r in j["models"]:
        assert r["psnr_db"] is None and r["psnr_reason"] == "no image pass", r
        assert r["rate_uniform"]["median"] > 0 and r["rate_varying"]["median"] > 0, r
        assert r["n_16_1000"]["max_rel"] <= r["n_2_1000"]["max_rel"] * (1 + 1e-12)
    rows = open(d + "/frontier.csv").read().strip().split("\n")
    assert len(rows) == 4 and rows[0].startswith("model,"), rows


# ---- test_gate_papers.sh -----------------------------------------------------------------------

@check
def gate_papers_papers_result_files(*args):
    """test_gate_papers.sh: papers.json result files"""
    import json, sys, xml.etree.ElementTree as ET
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    assert d["summary"]["failed"] == 0 and d["summary"]["passed"] == d["summary"]["gates"]
    # Every gate there carries both bounds, and the claimed figure (where a paper gives one) is
    # reported beside the measured one, never used as a bound.
    for g in d["gates"]:
        assert g["min"] is not None and g["max"] is not None, g
        assert "note" in g
    root = ET.parse(argv[2]).getroot()
    assert root.get("failures") == "0" and root.get("tests") == str(d["summary"]["gates"])


@check
def gate_papers_papers_figures_against_independent_values(*args):
    """test_gate_papers.sh: papers.json figures against independent values"""
    import json, math, subprocess, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    indep = argv[2]
    def coef(n):    # paper 2: 1/(2 pi int_0^min(1,1/k) (1 - k t)^2 (1 - t) dt), k = 0.448n + 0.099, by hand
        k = 0.448 * n + 0.099
        return 1 / (2 * math.pi * (0.5 - k / 3 + k * k / 12 if k <= 1 else 1 / (3 * k) - 1 / (12 * k * k)))
    bad = []
    for g in d["gates"]:
        lo, hi = int(g["n_min"]), int(g["n_max"])
        assert g["n_step"] == 1, g
        if g["model"] == "fq2n":
            ns = range(lo, hi + 1)
            if g["metric"] == "energy.max_abs_dev":      # max |0.214 (0.807 + n) / coef(n) - 1|
                want, tol = max(abs(0.214 * (0.807 + n) / coef(n) - 1) for n in ns), 1e-9
            else:                                         # albedo at normal incidence, the largest
                want, tol = max(0.214 * (0.807 + n) / coef(n) for n in ns), 2e-5   # device quadrature's bound
        else:
            spec = g["label"].replace("Q=", "").replace("k=", "")
            b = json.loads(subprocess.run([indep, "maxima", str(lo), str(hi), spec], check=True, capture_output=True,
                                          text=True).stdout)[0]
            want = b["max_rel"] if g["metric"] == "epicentre.max_rel" else b["att_max_abs"]
            want_n = b["max_rel_n"] if g["metric"] == "epicentre.max_rel" else b["att_n"]
            tol = 1e-9 * want
            if g["at_n"] != want_n:
                bad.append("%s: at n = %s, brute force %s" % (g["name"], g["at_n"], want_n))
        if abs(g["measured"] - want) > tol:
            bad.append("%s: measured %r, derived here %r" % (g["name"], g["measured"], want))
        if not (g["min"] <= want <= g["max"]):
            bad.append("%s: the pinned bounds [%r, %r] exclude the derived %r" % (g["name"], g["min"], g["max"], want))
    for b in bad:
        print("FAIL:", b)
    assert not bad and len(d["gates"]) == 16, len(d["gates"])


# ---- test_cli_accuracy.sh ----------------------------------------------------------------------

@check
def cli_accuracy_accuracy_contract(*args):
    """check_json of test_cli_accuracy.sh: accuracy.json contract"""
    import subprocess
    import math
    argv = ["check_json", *args]
    d = load(argv[1])
    has_context(d, "brdfbench.accuracy/1", ("date", "device", "platform_version", "build_options", "git_revision", "grid"))
    ctx = d["context"]
    assert ctx["grid"]["n_min"] == 2 and ctx["grid"]["n_max"] == 50 and ctx["grid"]["samples_per_zone"] == 256
    res = d["results"]
    assert [r["model"] for r in res] == ["cq2", "fq", "lyon"]
    assert res[1]["params"] == {"Q": 0.64} and res[2]["params"] == {"k": 3}
    # Each figure against tests/indep.c's brute force (grid + golden section over both zones of
    # every n, from the formulas written a second time in tests/lobe_formulas.h), with its n.
    out = subprocess.run([argv[2], "maxima", "2", "50", "cq2", "fq:0.64", "lyon:3"], check=True,
                         capture_output=True, text=True).stdout
    for r, b in zip(res, json.loads(out)):
        assert r["n_min"] == 2 and r["n_max"] == 50
        whole = max(b["att_max_abs"], b["epi_max_abs"])
        for zone, metric, want in (("epicentre", "max_rel", b["max_rel"]), ("attenuation", "max_abs", b["att_max_abs"]),
                                   ("whole", "max_abs", whole)):
            z = r[zone]
            assert abs(z[metric] - want) <= 1e-7 * want, (r["model"], zone, z, want)
            assert 2 <= z["at_n"] <= 50 and 0 <= z["at_x"] <= 1.5707963267948966 + 1e-12
        assert r["epicentre"]["at_n"] == b["max_rel_n"] and r["attenuation"]["at_n"] == b["att_n"], (r, b)
        # The device's grid samples the same function: never above the polished maximum beyond
        # float rounding (1e-5 relative).
        for zone, metric in (("epicentre", "max_rel"), ("attenuation", "max_abs"), ("whole", "max_abs")):
            assert r[zone]["grid_" + metric] <= r[zone][metric] * (1 + 1e-5), (r["model"], zone, r[zone])
        # The whole range's max |error| is the larger of the two zones' (zones partition [0, pi/2]).
        assert r["whole"]["max_abs"] >= r["attenuation"]["max_abs"]
        assert r["check"]["in_4th_digit_units"] < 0.05
    # Both ends of the epicentre are grid points (README: x uniform over [0, x_e(n)], both ends
    # included). cq2's and lyon:k=3's delta grows up to the zone's end (the brute force puts their
    # maxima at x_e(n)), so there the grid holds the maximum itself, to float rounding.
    for r, b in zip(res, json.loads(out)):
        xe = math.acos(math.exp(-0.511 / b["max_rel_n"]))
        if abs(b["max_rel_x"] - xe) < 1e-9 * xe:
            e = r["epicentre"]
            assert abs(e["grid_max_rel"] - e["max_rel"]) <= 1e-5 * e["max_rel"], (r["model"], e)
            assert abs(e["at_x"] - xe) <= 1e-9, (r["model"], e, xe)
    assert sum(1 for b in json.loads(out) if abs(b["max_rel_x"] - math.acos(math.exp(-0.511 / b["max_rel_n"]))) < 1e-9) == 2
    # cq2 at n = 50: its epicentre maximum is at the zone end (closed form: see test_accuracy.c);
    # the range maximum is at the largest n, where x_e = acos(exp(-0.511/50)).
    u = -math.expm1(-0.511 / 50)
    expect = 1 - (1 - 50 * u / 2) ** 2 / math.exp(-0.511)
    assert abs(res[0]["epicentre"]["max_rel"] - expect) < 1e-12, (res[0]["epicentre"], expect)
    assert res[0]["epicentre"]["at_n"] == 50


@check
def cli_accuracy_invalid_values_folded_into_maxima(*args):
    """test_cli_accuracy.sh: invalid values folded into maxima"""
    import json, math, sys
    argv = ["-", *args]
    r = json.load(open(argv[1]))["results"][0]
    assert r["status"] == "invalid_values" and r["invalid"]["count"] > 0, r
    # the first invalid point lies past c = 0.5, i.e. x > pi/3
    assert r["invalid"]["at_x"] > math.pi / 3 - 1e-6, r["invalid"]
    assert r["attenuation"]["max_abs"] < 1e-6 and r["whole"]["max_abs"] < 1e-6, r


# ---- test_throughput_cli.sh --------------------------------------------------------------------

@check
def throughput_cli_throughput_contract(*args):
    """check_json of test_throughput_cli.sh: throughput.json contract"""
    argv = ["check_json", *args]
    d = load(argv[1])
    has_context(d, "brdfbench.throughput/3", ("date", "device", "platform_version", "build_options", "git_revision", "throughput"))
    ctx = d["context"]
    assert ctx["throughput"]["reps"] == 2 and ctx["throughput"]["work_items"] == 4
    assert [b["variant"] for b in d["builds"]] == ["default", "denorms-are-zero"]
    pk = d["peak"]
    # an FMA is 2 flops (kernels/peak.cl counts 2 flops per lane and step)
    assert pk["status"] == "ok" and abs(pk["fma_per_s"] - pk["flops_per_s"]["median"] / 2) <= 1e-9 * pk["fma_per_s"], pk
    rows = d["results"]
    # The runner (host/core/runner.h): --reps 2 rounds, the peak kernel three times per round (at
    # the round's start, middle and end), its rates kept in round order; each row's normalised
    # rate of round k is its rate over the median of the peak's three rates of round k, recomputed
    # here from the two arrays.
    rn = ctx["throughput"]["runner"]
    assert rn["rounds"] == 2 and rn["launches"] > 0 and rn["preemption_retries"] >= 0, rn
    pr = pk["flops_per_s_reps"]
    assert len(pr) == 3 * 2, pr
    ref = [sorted(pr[3 * k:3 * k + 3])[1] for k in range(2)]
    for r in d["results"]:
        if r["status"] != "ok":
            continue
        assert len(r["normalised_reps"]) == 2, r["normalised_reps"]
        for k in range(2):
            x, y = r["normalised_reps"][k], r["evals_per_s_reps"][k] / ref[k]
            assert abs(x - y) <= 1e-12 * y, (r["label"], k, x, y)
        # a CPU device: the rates per CPU second too, and the CPU seconds of each repetition
        assert len(r["normalised_cpu_reps"]) == 2 and len(r["cpu_seconds_reps"]) == 2, r
        assert r["timer"] == "profiling events", r["timer"]
    # pow + 3 models; default: uniform and varying; denorms-are-zero: uniform
    assert len(rows) == 4 * 2 + 4, len(rows)
    assert [r["label"] for r in rows[:8:2]] == ["pow", "phong", "cq2", "fq:Q=0.7"], [r["label"] for r in rows]
    def med(r): return r["evals_per_s"]["median"]
    def same(r, label): return [x for x in rows if x["label"] == label and x["variant"] == r["variant"] and x["n_mode"] == r["n_mode"]][0]
    def close(x, y, what): assert x is not None and abs(x - y) <= 1e-9 * abs(y), "%s: %r vs %r recomputed" % (what, x, y)
    # The derived columns, recomputed from the medians (README's definitions): the ratio to pow() in
    # the same variant and n mode, to the model's own reference (docs/definitions.md: the Phong lobe c^n for
    # every model here), to the tuned C loop's median, and the fraction of the FMA peak.
    for r in rows:
        assert r["status"] == "ok", r
        e = r["evals_per_s"]
        assert 0 < e["min"] <= e["median"] <= e["max"], e
        # every repetition is kept (--reps 2), and min/median/max are taken over them
        reps = sorted(r["evals_per_s_reps"])
        assert len(reps) == 2, reps
        assert math.isclose(reps[0], e["min"], rel_tol=1e-12) and math.isclose(reps[-1], e["max"], rel_tol=1e-12), (reps, e)
        # the median of rates is the rate of the median time: with 2 reps, work over the mean time (harmonic mean)
        assert math.isclose(e["median"], 2 / (1 / reps[0] + 1 / reps[1]), rel_tol=1e-9), (reps, e)
        if r["variant"] == "default":
            assert len(r["host_c"]["evals_per_s_reps"]) == 2, r["host_c"]
        close(r["ratio_to_reference"], med(r) / med(same(r, "pow")), r["label"] + " ratio_to_reference")
        close(r["fraction_of_peak"], med(r) / pk["fma_per_s"], r["label"] + " fraction_of_peak")
        if r["label"] != "pow":
            close(r["ratio_to_model_reference"], med(r) / med(same(r, "phong")), r["label"] + " ratio_to_model_reference")
        assert r["build_options"] == ("" if r["variant"] == "default" else "-cl-denorms-are-zero")
        assert r["accuracy"]["status"] == "ok" and r["accuracy"]["max_diff_of_peak"] < 1e-5
        if r["variant"] == "default":
            assert r["host_c"]["status"] == "ok", r
            close(r["ratio_to_host_c"], med(r) / r["host_c"]["evals_per_s"]["median"], r["label"] + " ratio_to_host_c")
    sw = d["sweep"]
    assert sw["status"] == "ok" and sw["n_count"] == 11, sw
    # the sweep's speed-up: tuned C's time over the device's, in total and per model
    close(sw["speedup_vs_host_c"], sw["host_c_seconds"] / sw["device_seconds"], "sweep speedup_vs_host_c")
    assert abs(sw["device_seconds"] - sum(m["device_seconds"]["median"] for m in sw["models"])) <= 1e-9 * sw["device_seconds"]
    assert abs(sw["host_c_seconds"] - sum(m["host_c_seconds"]["median"] for m in sw["models"])) <= 1e-9 * sw["host_c_seconds"]
    for m in sw["models"]:
        close(m["speedup_vs_host_c"], m["host_c_seconds"]["median"] / m["device_seconds"]["median"], m["label"] + " sweep speed-up")


@check
def throughput_cli_failed_variant_rows(*args):
    """test_throughput_cli.sh: failed variant rows"""
    import json, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    b = {x["variant"]: x for x in d["builds"]}
    assert b["default"]["status"] == "ok" and b["fast-relaxed-math"]["status"] == "failed", b
    for r in d["results"]:
        if r["variant"] == "fast-relaxed-math":
            assert r["status"] == "failed" and "build" in r["reason"] and r["evals_per_s"]["median"] is None, r
        else:
            assert r["status"] == "ok", r


@check
def throughput_cli_ab_options_two_sides(*args):
    """test_throughput_cli.sh: --ab-options: the two sides"""
    import json, sys
    argv = ["-", *args]
    full, a, b = (json.load(open(argv[1] + f)) for f in ("/throughput.json", "/ab/a/throughput.json", "/ab/b/throughput.json"))
    assert {r["variant"] for r in full["results"]} == {"default", "ab"}, {r["variant"] for r in full["results"]}
    key = lambda r: (r["label"], r["variant"], r["n_mode"])
    assert sorted(map(key, a["results"])) == sorted(map(key, b["results"])) and len(a["results"]) == 3 * 2
    assert all(len(r["normalised_cpu_reps"]) == 3 for r in a["results"] + b["results"])
    assert b["context"]["ab"]["side"] == "b" and "-cl-fast-relaxed-math" in b["context"]["build_options"]
    assert a["context"]["build_options"] == "" and a["peak"]["flops_per_s_reps"] == b["peak"]["flops_per_s_reps"]
    ab = {(r["label"], r["n_mode"]): r for r in full["results"] if r["variant"] == "ab"}
    for r in b["results"]:
        assert r["evals_per_s_reps"] == ab[(r["label"], r["n_mode"])]["evals_per_s_reps"]


# ---- test_compare.sh ---------------------------------------------------------------------------

@check
def compare_scaled_run_factor_verdicts(*args):
    """test_compare.sh: scaled run: factor and verdicts"""
    import json, math, sys
    argv = ["-", *args]
    def no_const(x): raise ValueError("non-finite number in JSON: " + x)
    d = json.load(open(argv[1]), parse_constant=no_const)
    f = float(argv[2])
    assert d["schema"] == "brdfbench.compare/1"
    assert [r["name"] for r in d["runs"]] == ["a", "slow"]
    rows = [r for r in d["rows"] if r["kind"] == "throughput" and r["model"] != "peak"]
    assert len(rows) == 2 * 4, len(rows)   # pow, cq2, fq2, phong x uniform, varying
    for r in rows:
        base, cand = r["cells"]
        assert base["verdict"] == "baseline" and math.isclose(base["ratio"], 1.0)
        assert math.isclose(cand["ratio"], f, rel_tol=1e-12), (r["key"], cand["ratio"], f)
        # 5 repetitions each, fully separated: exact two-sided p = 2 / C(10, 5) = 2/252
        assert cand["verdict"] == "slower", (r["key"], cand)
        assert math.isclose(cand["p"], 2 / 252, rel_tol=1e-12), cand["p"]
    print("factor %.4g reported on %d rows" % (f, len(rows)))


@check
def compare_csv_rows(*args):
    """test_compare.sh: compare.csv"""
    import csv, sys
    argv = ["-", *args]
    rows = [r for r in csv.DictReader(open(argv[1])) if r["key"] != "peak (reference kernel)"]
    assert len(rows) == 2 * 8, len(rows)
    assert {r["run"] for r in rows} == {"a", "slow"}
    assert all(r["verdict"] == "slower" for r in rows if r["run"] == "slow")


@check
def compare_reversed_faster(*args):
    """test_compare.sh: reversed: faster"""
    import json, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    assert all(r["cells"][1]["verdict"] == "faster" for r in d["rows"] if r["model"] != "peak"), d["rows"]


@check
def compare_self_ratio_1_same(*args):
    """test_compare.sh: self: ratio 1 and same"""
    import json, math, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    # the model rows and the run's peak (its reference kernel) as a row of its own
    assert len(d["rows"]) == 8 + 1 and d["rows"][0]["key"] == "peak (reference kernel)", [r["key"] for r in d["rows"]]
    for r in d["rows"]:
        c = r["cells"][1]
        # identical repetitions: every value tied with its copy, U = 12.5 = E U, p = 1, ratio 1;
        # "same" when the ratio's interval lies within the threshold's band (compare.h; here 0, from
        # --fail-if-slower 0), "noisy" when the run's own spread makes it wider than the band
        assert c["ratio"] == 1.0 and c["p"] == 1.0, (r["key"], c)
        wide = math.log(c["ratio_ci_hi"]) - math.log(c["ratio_ci_lo"]) > 2 * math.log1p(d["threshold"])
        assert c["verdict"] == ("noisy" if wide else "same"), (r["key"], c)
    assert d["runs"][1]["context_differs"] == [], d["runs"][1]["context_differs"]


@check
def compare_3_repetitions_undecided(*args):
    """test_compare.sh: 3 repetitions: undecided"""
    import json, math, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    for r in d["rows"]:
        if r["model"] == "peak":
            continue
        c = r["cells"][1]
        # fully separated, yet p = 2/20: the test cannot reach 0.05 with these sizes
        assert c["verdict"] == "undecided" and math.isclose(c["p"], 0.1), (r["key"], c)


@check
def compare_two_real_runs(*args):
    """test_compare.sh: two real runs"""
    import json, math, sys
    argv = ["-", *args]
    d, a, b = (json.load(open(p)) for p in argv[1:4])
    med = lambda doc: {(r["label"], r["variant"], r["n_mode"]): r["normalised_cpu_reps"] for r in doc["results"]}
    ma, mb = med(a), med(b)
    def hl_ratio(x, y):
        q = sorted(math.log(u) - math.log(v) for u in x for v in y)
        n = len(q)
        return math.exp(q[n // 2] if n % 2 else 0.5 * (q[n // 2 - 1] + q[n // 2]))
    rows = [r for r in d["rows"] if r["model"] != "peak"]
    assert len(rows) == len(ma) == len(mb) == 8
    verdicts = []
    for r in rows:
        label, variant, mode = [s.strip() for s in r["key"].split("|")]
        key = (label, variant, mode.replace("n ", ""))
        c = r["cells"][1]
        assert math.isclose(c["ratio"], hl_ratio(mb[key], ma[key]), rel_tol=1e-12), (key, c["ratio"])
        assert c["basis"] == "normalised per CPU second", c["basis"]
        assert c["verdict"] in ("same", "faster", "slower", "noisy"), c["verdict"]
        assert 0 < c["p"] <= 1
        verdicts.append(c["verdict"])
    print("two real runs: %d of %d rows same (%s)" % (verdicts.count("same"), len(verdicts),
          ", ".join("%s %d" % (v, verdicts.count(v)) for v in sorted(set(verdicts)))))


@check
def compare_mismatched_rows_listed(*args):
    """test_compare.sh: mismatched rows listed"""
    import json, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    by = {r["key"]: r for r in d["rows"]}
    assert len(d["rows"]) == 8 + 1 + 1, len(d["rows"])   # 6 shared, 2 phong, 1 lyon, the peak
    for k in ("phong | default | n uniform", "phong | default | n varying"):
        assert not by[k]["in_all_runs"] and by[k]["cells"][1]["status"] == "missing" and by[k]["cells"][1]["verdict"] == "missing"
    lyon = by["lyon:k=3 | default | n varying"]   # a copy of the last row, fq2 with n varying
    assert lyon["cells"][0]["status"] == "missing" and lyon["cells"][1]["status"] == "ok"
    assert sum(r["in_all_runs"] for r in d["rows"]) == 6 + 1


@check
def compare_accuracy_verdicts(*args):
    """test_compare.sh: accuracy verdicts"""
    import json, math, sys
    argv = ["-", *args]
    d, a, b = (json.load(open(p)) for p in argv[1:4])
    val = lambda doc, label, fig: [r for r in doc["results"] if r["label"] == label][0][fig.split(".")[0]][fig.split(".")[1]]
    seen = 0
    for r in d["rows"]:
        label = r["key"].split(" | ")[0]
        va, vb = val(a, label, r["metric"]), val(b, label, r["metric"])
        c = r["cells"][1]
        # the 4th significant digit, as printed with 4 digits
        same = "%.3e" % va == "%.3e" % vb
        want = "unchanged" if same else ("changed, better" if vb < va else "changed, worse")
        assert c["verdict"] == want, (r["key"], r["metric"], c["verdict"], want)
        assert math.isclose(c["change"], vb - va, rel_tol=1e-9, abs_tol=1e-300), (c["change"], vb - va)
        seen += 1
    assert seen == 6, seen
    verd = {(r["key"].split(" | ")[0], r["metric"]): r["cells"][1]["verdict"] for r in d["rows"]}
    assert verd[("cq2", "epicentre.max_rel")] == "changed, worse"
    assert verd[("cq2", "attenuation.max_abs")] == "changed, better"
    assert verd[("fq2", "epicentre.max_rel")] == "unchanged"


@check
def compare_render_verdicts(*args):
    """test_compare.sh: render verdicts"""
    import json, math, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    by = {(r["key"], r["metric"]): r for r in d["rows"]}
    sp = by[("spheres | cq2", "mpixel_per_s@96x54")]["cells"]
    # r2 takes twice as long: ratio 1/2, ranges [1.8, 2.2] ms vs [0.9, 1.1] ms apart: slower;
    # r3 at 1.05 ms overlaps r1's range: same
    assert math.isclose(sp[1]["ratio"], 0.5) and sp[1]["verdict"] == "slower", sp[1]
    assert math.isclose(sp[2]["ratio"], 1 / 1.05) and sp[2]["verdict"] == "same", sp[2]
    ps = by[("spheres 96x54 | cq2", "psnr_db")]["cells"]
    assert ps[1]["verdict"] == "changed, worse" and math.isclose(ps[1]["change"], -1.0), ps[1]
    assert ps[2]["verdict"] == "unchanged"
    assert ("spheres 96x54 | phong", "psnr_db") not in by   # infinite PSNR of identical images: no row
    assert by[("spheres 96x54 | phong", "max_abs")]["cells"][1]["verdict"] == "unchanged"


@check
def compare_render_verdicts_from_launches_rates(*args):
    """test_compare.sh: render verdicts from the launches' rates"""
    import json, math, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    sp = {(r["key"], r["metric"]): r for r in d["rows"]}[("spheres | cq2", "mpixel_per_s@96x54")]["cells"]
    # the rank test on 5 rates each: r5's all below r4's: p = 2 / C(10, 5) = 2/252 (exact two-sided);
    # r6's the same values as r4's: p = 1, ratio 1, but its interval (5 vs 5 at 0.05: the 3rd
    # smallest and largest of the 25 ratios m_j / m_i of (0.9, 0.95, 1, 1.05, 1.1): 0.95 / 1.1 and
    # 1.1 / 0.95) is wider than the 10% band: noisy
    assert sp[1]["verdict"] == "slower" and math.isclose(sp[1]["p"], 2 / 252), sp[1]
    assert sp[2]["verdict"] == "noisy" and sp[2]["p"] == 1.0, sp[2]
    assert math.isclose(sp[2]["ratio_ci_lo"], 0.95 / 1.1) and math.isclose(sp[2]["ratio_ci_hi"], 1.1 / 0.95), sp[2]


@check
def compare_frontier_rows(*args):
    """test_compare.sh: frontier rows"""
    import json, math, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    by = {(r["key"], r["metric"]): r["cells"][1] for r in d["rows"]}
    assert math.isclose(by[("fq2", "evals_per_s")]["ratio"], 0.5)
    assert by[("fq2", "evals_per_s")]["verdict"] == "slower"           # 5 reps each, apart: p = 2/252
    assert math.isclose(by[("fq2", "evals_per_s")]["p"], 2 / 252)
    assert by[("fq2", "max_rel")]["verdict"] == "changed, worse"         # 1.257e-2 -> 1.260e-2
    assert by[("fq2", "max_abs")]["verdict"] == "unchanged"
    assert by[("cq2", "evals_per_s")]["verdict"] == "same"              # no reps: ranges overlap (equal)


@check
def compare_kernel_fingerprints_in_context(*args):
    """test_compare.sh: kernel fingerprints in the context"""
    import json, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    assert "kernel sources" not in d["runs"][1]["context_differs"], d["runs"][1]   # the same files
    assert "kernel sources" in d["runs"][2]["context_differs"], d["runs"][2]       # one comment added
    assert "brdf_models.h" in d["runs"][2]["context"]["kernel sources"]


@check
def compare_fit_rows(*args):
    """test_compare.sh: fit rows"""
    import json, sys
    argv = ["-", *args]
    d, f = (json.load(open(p)) for p in argv[1:3])
    rows = [r for r in d["rows"] if r["kind"] == "fit"]
    best = {r["metric"]: r["cells"][1]["verdict"] for r in rows if r["key"].startswith("best affine")}
    assert best == {"a": "changed", "b": "unchanged", "max_rel": "changed, better", "max_abs": "unchanged"}, best
    # every model fit.json compares with, except the fitted quad: itself, by its moving label
    others = sorted(r["key"].split(" | ")[0] for r in rows if r["metric"] == "max_rel" and " | n " in r["key"]
                    and not r["key"].startswith(("best", "capped")))
    want = sorted(m["model"] for m in f["compare"] if not m["model"].startswith("quad:"))
    assert others == want and len(want) > 0, (others, want)


@check
def compare_device_0_0_rows_tagged(*args):
    """test_compare.sh: --device 0,0: rows tagged"""
    import json, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    assert d["schema"] == "brdfbench.throughput/3"
    devs = d["context"]["devices"]
    assert [x["index"] for x in devs] == ["0:0", "0:0"], devs
    name = devs[0]["device"]
    # the second mention of the same device is told apart by its place in the list
    assert [x["tag"] for x in devs] == [name, name + " #2"], devs
    tags = [r["device"] for r in d["results"]]
    assert tags == [name] * 8 + [name + " #2"] * 8, tags


@check
def compare_devices_side_by_side(*args):
    """test_compare.sh: devices side by side"""
    import json, math, sys
    argv = ["-", *args]
    d, t = (json.load(open(p)) for p in argv[1:3])
    assert d["layout"] == "devices of one run"
    name = t["context"]["devices"][0]["device"]
    assert [r["name"] for r in d["runs"]] == [name, name + " #2"]
    assert len(d["rows"]) == 8 + 1 and all(r["in_all_runs"] and r["device"] == "" for r in d["rows"])
    # two devices are compared on what they deliver: the absolute rates (normalised ones compare a
    # device with itself)
    med = {(r["device"], r["label"], r["variant"], r["n_mode"]): r["evals_per_s_reps"] for r in t["results"]}
    def hl_ratio(x, y):   # the median of the ratios y_j / x_i, on logarithms
        q = sorted(math.log(v) - math.log(u) for u in x for v in y)
        n = len(q)
        return math.exp(q[n // 2] if n % 2 else 0.5 * (q[n // 2 - 1] + q[n // 2]))
    for r in d["rows"]:
        if r["model"] == "peak":
            continue
        label, variant, mode = [s.strip() for s in r["key"].split("|")]
        a = med[(name, label, variant, mode[2:])]
        b = med[(name + " #2", label, variant, mode[2:])]
        assert math.isclose(r["cells"][1]["ratio"], hl_ratio(a, b), rel_tol=1e-12)


@check
def compare_dev_against_dev_rows_keyed(*args):
    """test_compare.sh: dev against dev: rows keyed by device"""
    import json, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    assert len(d["rows"]) == 2 * (8 + 1) and len({r["device"] for r in d["rows"]}) == 2
    assert all(r["cells"][1]["verdict"] in ("same", "noisy") and r["cells"][1]["ratio"] == 1.0 for r in d["rows"])


@check
def compare_accuracy_rows_tagged(*args):
    """test_compare.sh: accuracy rows tagged"""
    import json, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    assert d["schema"] == "brdfbench.accuracy/1" and len(d["results"]) == 2
    assert d["results"][1]["device"] == d["results"][0]["device"] + " #2"


# ---- test_hostile.sh ---------------------------------------------------------------------------

@check
def hostile_nan_model_never_measured(*args):
    """test_hostile.sh: a NaN model reads as measured somewhere (above)"""
    import json, sys
    argv = ["-", *args]
    bad = []
    tp = json.load(open("nanrun/throughput.json"))
    for r in tp["results"]:
        if r["label"] == "nanm" and (r["status"] == "ok" or not r.get("reason") or r["accuracy"]["status"] == "ok"):
            bad.append("throughput row %s %s: status %s" % (r["label"], r["n_mode"], r["status"]))
    acc = json.load(open("nanrun/accuracy.json"))
    bad += ["accuracy %s ok" % r["label"] for r in acc["results"] if r["label"] == "nanm" and r["status"] == "ok"]
    for sc in json.load(open("nanrun/render.json"))["scenes"]:
        for m in sc["models"]:
            mt = m["metrics"]
            if m["model"] == "nanm" and (mt["max_abs"] is not None or mt.get("status") != "nonfinite"):
                bad.append("render %s: max_abs %r status %r" % (sc["scene"], mt["max_abs"], mt.get("status")))
    for r in json.load(open("nanrun/frontier.json"))["models"]:
        if r["model"] == "nanm" and (r["status"] == "ok" or r["on_front"] or
                                     any(r[k]["max_rel"] is not None for k in ("n_2_1000", "n_16_1000"))):
            bad.append("frontier: %r" % r)
    rep = open("nanrun/report.md").read()
    if "| nanm | uniform | - | failed |" not in rep:
        bad.append("report.md shows a rate for nanm")
    if bad:
        print("\n".join(bad), file=sys.stderr)
        sys.exit(1)


@check
def hostile_throughput_sweep_agreement(*args):
    """test_hostile.sh: throughput sweep agreement: exit $rc: $(head -c 300 err)"""
    import json
    argv = ["-", *args]
    s = json.load(open("tsw/throughput.json"))["sweep"]
    assert s["agreement_excludes"] == ["phongpow"], s["agreement_excludes"]
    own = max(m["agreement_max_rel_diff"] for m in s["models"] if m["label"] != "phongpow")
    assert s["agreement_max_rel_diff"] == own, (s["agreement_max_rel_diff"], own)


# ---- test_reproduce_cli.sh ---------------------------------------------------------------------

@check
def reproduce_cli_claims_q_sweep(*args):
    """test_reproduce_cli.sh: claims.json / q_sweep.json contract and values"""
    import json, math, sys
    argv = ["-", *args]
    d = argv[1]
    def no_const(x): raise ValueError("non-finite number in JSON: " + x)
    c = json.load(open(d + "/claims.json"), parse_constant=no_const)
    assert c["schema"] == "brdfbench.claims/1"
    for k in ("date", "device", "git_revision", "grid"):
        assert k in c["context"], k
    rows = {r["id"]: r for r in c["claims"]}
    need = ["P1-eq11-lhs", "P1-eq12-a", "P1-eq12-b", "P1-eq12-c", "P1-xi", "P1-xi64", "P1-fig3-fvol", "P1-4.5x",
            "P1-fig5-zone", "P2-fq", "P2-fq2-rel", "P2-fq2-abs", "P2-f2-rel", "P2-f2-abs", "P2-6.3x", "P2-fig4",
            "P2-fit-k-a", "P2-fit-k-b", "P2-fig2-Q", "P2-coef-2", "P2-coef-3", "P2-coef-4", "P2-coef-10",
            "P2-coef-fit-a", "P2-coef-fit-b", "P2-coef-dev", "P2-energy", "P2-reciprocity"]
    for k in need:
        assert k in rows, "missing row " + k
    for r in c["claims"]:
        for k in ("id", "kind", "source", "claim", "claimed_text", "measured_text", "tolerance", "verdict", "note", "method"):
            assert k in r, (r["id"], k)
        assert r["verdict"] in ("reproduced", "not reproduced"), r["verdict"]
        if r["measured"] is None:
            assert "measured_reason" in r
    s = c["summary"]
    assert s["rows"] == len(c["claims"]) == s["reproduced"] + s["not_reproduced"]

    # Left side of eq. 11: inner integral in closed form (1 - c_e^(n+2))/(n+2), c_e = exp(-0.511/n),
    # outer by Simpson over n in [16, 256].
    def lhs(n): return -math.expm1(-0.511 * (n + 2) / n) / (n + 2)
    P = 4000; h = 240.0 / P
    simp = (lhs(16) + lhs(256) + sum((4 if i % 2 else 2) * lhs(16 + i * h) for i in range(1, P))) * h / 3
    assert abs(rows["P1-eq11-lhs"]["measured"] - simp) < 1e-8, (rows["P1-eq11-lhs"]["measured"], simp)
    assert rows["P1-eq11-lhs"]["verdict"] == "reproduced"          # 1.09848 is 1.098 to its printed digits

    # coef(2): k = 0.995 <= 1, I = 1/2 - k/3 + k^2/12, coef = 1/(2 pi I); the paper's fit deviates by
    # 0.214 (2.807) / coef(2) - 1 there.
    k = 0.448 * 2 + 0.099
    coef2 = 1 / (2 * math.pi * (0.5 - k / 3 + k * k / 12))
    assert abs(rows["P2-coef-2"]["measured"] - coef2) < 1e-9
    assert abs(rows["P2-coef-dev"]["measured"] - abs(0.214 * 2.807 / coef2 - 1)) < 1e-9

    # Fig. 4: k_Q(2) = (sqrt(Q) - 1)/(Q^(1/2) - 1) = 1 exactly, the fit gives 0.995: 0.5% at n = 2.
    assert abs(rows["P2-fig4"]["measured"] - 0.005) < 1e-12

    # f2's max delta sits at the zone end of n = 1000: u = 1 - exp(-0.511/n), delta = 1 - (1 - n u/2)^2 / exp(-0.511).
    n = 1000.0; u = -math.expm1(-0.511 / n)
    f2 = 1 - (1 - n * u / 2) ** 2 / math.exp(-0.511)
    assert abs(rows["P2-f2-rel"]["measured"] - f2) < 1e-9, (rows["P2-f2-rel"]["measured"], f2)
    assert rows["P2-f2-rel"]["verdict"] == "not reproduced"       # 7.588% against the claimed 7.924%

    # xi: the smaller root of the measured quadratic, recomputed from the measured coefficients.
    a, b, cc = rows["P1-eq12-a"]["measured"], rows["P1-eq12-b"]["measured"], rows["P1-eq12-c"]["measured"]
    root = (-b - math.sqrt(b * b - 4 * a * (cc - rows["P1-eq11-lhs"]["measured"]))) / (2 * a)
    assert abs(rows["P1-xi"]["measured"] - root) < 1e-12

    q = json.load(open(d + "/q_sweep.json"), parse_constant=no_const)
    assert q["schema"] == "brdfbench.q_sweep/1"
    assert len(q["Q"]) == len(q["max_rel"]) == len(q["max_abs"]) == len(q["max_abs_attenuation"]) > 10
    assert q["context"]["grid"]["q_step"] == 0.05 and q["context"]["grid"]["samples_per_zone"] == 256
    # the refined minimiser is no worse than any Q of the sweep's grid
    assert q["best"]["max_rel"] <= min(q["max_rel"]) + 1e-9

    e = json.load(open(d + "/energy.json"), parse_constant=no_const)
    assert e["schema"] == "brdfbench.energy/1"
    assert len(e["reciprocity_image_pass"]["models"]) > 0 and len(e["albedo"]["models"]) > 0
    md = open(d + "/claims.md").read()
    assert "| id | source | claim | claimed | measured | tolerance | verdict | where / why |" in md


@check
def reproduce_cli_fit_against_indep(*args):
    """test_reproduce_cli.sh: check"""
    import json, subprocess, sys
    argv = ["-", *args]
    def no_const(x): raise ValueError(x)
    f = json.load(open(argv[1]), parse_constant=no_const)
    indep = argv[2]
    assert f["schema"] == "brdfbench.fit/1"
    for k in ("a", "b", "max_rel", "max_abs", "limit", "model"):
        assert k in f, k
    lim = f["limit"]
    assert len(lim) == 999 and lim[0]["n"] == 2 and abs(lim[0]["k"] - 1) < 1e-9 and lim[0]["max_rel"] < 1e-12
    assert all(set(p) == {"n", "k", "max_rel"} for p in lim)
    def brute(*specs):   # tests/indep.c: grid + golden section over both zones of every n in [2, 1000]
        out = subprocess.run([indep, "maxima", "2", "1000"] + list(specs), check=True, capture_output=True, text=True).stdout
        return json.loads(out)
    def close(x, y, rel, what):
        assert abs(x - y) <= rel * abs(y), "%s: %r vs %r derived here" % (what, x, y)
    # The family's limit at n = 1000, the end where every affine fit's max delta sits: the per-n
    # minimax k by golden section on tests/indep.c's brute force.
    L = json.loads(subprocess.run([indep, "limit", "1000"], check=True, capture_output=True, text=True).stdout)
    close(f["limit_overall"]["max_rel"], L["max_rel"], 1e-8, "the family's limit over [2, 1000]")
    close(lim[-1]["k"], L["k"], 1e-6, "per-n minimax k at n = 1000")
    fit, fq2, capped = brute("quad:%r,%r" % (f["a"], f["b"]), "fq2",
                             "quad:%r,%r" % (f["capped_at_fq2"]["a"], f["capped_at_fq2"]["b"]))
    # max delta and max Delta of the model fit.json names, recomputed from its a and b as written.
    close(f["max_rel"], fit["max_rel"], 1e-7, "fit max delta at the written (a, b)")
    close(f["max_abs"], fit["att_max_abs"], 1e-7, "fit max Delta at the written (a, b)")
    # The minimax affine fit reaches the family's limit (no k(n) does better at n = 1000, and the
    # line through k*(1000) with slope near 0.45 keeps every other n below it): max delta equals
    # L's, k(1000) = a 1000 + b is the minimax k there, and a is near the asymptotic slope 0.45
    # (docs/definitions.md: the n -> infinity minimax slope a m = 0.900 for m = 2).
    close(f["max_rel"], L["max_rel"], 1e-7, "fit max delta against the family's limit at n = 1000")
    close(f["a"] * 1000 + f["b"], L["k"], 1e-6, "k(1000) of the fit against the minimax k at n = 1000")
    assert abs(f["a"] - 0.45) < 2e-3, f["a"]
    # Capped at fq2's own max Delta (fq2 brute-forced here), the family only ties fq2's max delta
    # (fq2 is one of its members; README's claim): the capped point's figures at its written (a, b).
    c = f["capped_at_fq2"]
    fq2_abs = max(fq2["att_max_abs"], fq2["epi_max_abs"])
    close(c["max_abs_cap"], fq2_abs, 1e-7, "cap = fq2's max Delta")
    close(c["max_rel"], capped["max_rel"], 1e-7, "capped fit's max delta at its (a, b)")
    close(c["max_abs"], capped["att_max_abs"], 1e-7, "capped fit's max Delta at its (a, b)")
    assert capped["att_max_abs"] <= fq2_abs * (1 + 1e-9), "the capped fit breaks its cap"
    close(c["max_rel"], fq2["max_rel"], 1e-6, "capped fit ties fq2's max delta")
    # The trade-off: caps from fq2's max Delta to the uncapped fit's, each point within its cap,
    # its figures recomputed at its (a, b), max delta falling as the cap rises, from fq2's to the
    # uncapped fit's (the two ends derived above).
    pts = f["tradeoff"]["points"]
    assert len(pts) == 5, len(pts)
    got = brute(*["quad:%r,%r" % (p["a"], p["b"]) for p in pts])
    for p, g in zip(pts, got):
        close(p["max_rel"], g["max_rel"], 1e-7, "trade-off max delta at cap %r" % p["max_abs_cap"])
        close(p["max_abs"], g["att_max_abs"], 1e-7, "trade-off max Delta at cap %r" % p["max_abs_cap"])
        assert g["att_max_abs"] <= p["max_abs_cap"] * (1 + 1e-9), p
    for p, q in zip(pts, pts[1:]):
        assert q["max_abs_cap"] > p["max_abs_cap"] and q["max_rel"] < p["max_rel"], (p, q)
    close(pts[0]["max_abs_cap"], fq2_abs, 1e-7, "first cap")
    close(pts[0]["max_rel"], fq2["max_rel"], 1e-6, "first point ties fq2")
    close(pts[-1]["max_abs_cap"], fit["att_max_abs"], 1e-7, "last cap")
    close(pts[-1]["max_rel"], L["max_rel"], 1e-6, "last point reaches the limit")
    fq2c = [x for x in f["compare"] if x["model"] == "fq2"][0]
    close(fq2c["max_rel"], fq2["max_rel"], 1e-7, "fq2's max delta in compare")
    print(f["model"], f["max_rel"])


@check
def reproduce_cli_fitted_model_accuracy(*args):
    """test_reproduce_cli.sh: accuracy of the fitted model differs from fit.json"""
    import json, sys
    argv = ["-", *args]
    r = json.load(open(argv[1]))["results"][0]
    assert r["model"] == "quad"
    assert abs(r["epicentre"]["max_rel"] / float(argv[2]) - 1) < 1e-9, (r["epicentre"]["max_rel"], argv[2])


# ---- test_cli_flags.sh -------------------------------------------------------------------------

@check
def cli_flags_help_flags_read_alike(*args):
    """test_cli_flags.sh: a flag reads differently in two commands' --help"""
    import re, sys, collections
    argv = ["-", *args]
    folder, commands = argv[1], argv[2:]
    meaning = collections.defaultdict(dict)
    for c in commands:
        entries, cur = [], None
        for line in open(f"{folder}/help_{c}"):
            m = re.match(r"^  (--[a-z0-9-]+)(?: \S+)?\s*(.*)$", line.rstrip("\n"))
            if m:
                cur = [m.group(1), m.group(2)]
                entries.append(cur)
            elif cur and line.startswith(" " * 21):
                cur[1] = (cur[1] + " " + line.strip()).strip()
            else:
                cur = None
        for name, text in entries:
            text = re.sub(r"\s*\((?:[^()]|\([^()]*\))*\)$", "", text)   # the closing parenthesis
            meaning[name][c] = text
    bad = 0
    for name, per in sorted(meaning.items()):
        if len(set(per.values())) > 1:
            bad = 1
            print(f"{name} means different things: " + "; ".join(f"{c}: {t!r}" for c, t in per.items()), file=sys.stderr)
    # the flags the command line shares must be there, each in every command that runs sweeps
    for name in ["--n-min", "--n-max", "--n-step", "--samples", "--models", "--out", "--quiet"]:
        for c in ["accuracy", "all"]:
            if c not in meaning[name]:
                bad = 1
                print(f"{c} --help lacks {name}", file=sys.stderr)
    sys.exit(bad)


@check
def cli_flags_list_json_as_list(*args):
    """test_cli_flags.sh: list --json - differs from list"""
    import json, re, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    assert d["schema"] == "brdfbench.list/1", d["schema"]
    ids = [m["id"] for m in d["models"]]
    text_ids = re.findall(r"^  (\S+) +\S", open(argv[2]).read().split("OpenCL platforms")[0], re.M)
    assert ids == text_ids, (ids, text_ids)
    fq = [m for m in d["models"] if m["id"] == "fq"][0]
    assert [p["name"] for p in fq["parameters"]] == ["Q"], fq


@check
def cli_flags_accuracy_json_stdout_alone(*args):
    """test_cli_flags.sh: accuracy --json - is not the accuracy document alone"""
    import json, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    assert d["schema"].startswith("brdfbench.accuracy/"), d["schema"]
    assert [r["label"] for r in d["results"]] == ["fq2", "cq2"], [r["label"] for r in d["results"]]


@check
def cli_flags_accuracy_csv_stdout_alone(*args):
    """test_cli_flags.sh: accuracy --csv - is not the CSV alone: $(head -3 """
    import csv, sys
    argv = ["-", *args]
    rows = list(csv.reader(open(argv[1])))
    assert len(rows) == 1 + 5, len(rows)
    assert all(len(r) == len(rows[0]) for r in rows), "ragged rows"


@check
def cli_flags_throughput_csv_stdout_alone(*args):
    """test_cli_flags.sh: throughput --csv - is not the CSV alone: $(cat """
    import csv, sys
    argv = ["-", *args]
    rows = list(csv.DictReader(open(argv[1])))
    assert [r["model"] for r in rows] == ["pow", "fq2"], rows


@check
def cli_flags_all_applies_grid_flags(*args):
    """test_cli_flags.sh: all did not apply the grid flags"""
    import json, sys
    argv = ["-", *args]
    a = json.load(open(argv[1] + "/accuracy.json"))["results"][0]
    assert (a["n_min"], a["n_max"]) == (3, 40), (a["n_min"], a["n_max"])
    f = json.load(open(argv[1] + "/field_fq2.json"))["grid"]
    assert (f["n_min"], f["n_max"]) == (3, 40), f


# ---- test_fullbrdf_cli.sh ----------------------------------------------------------------------

@check
def fullbrdf_cli_bp_brdf_shaded_from_vectors(*args):
    """check_json of test_fullbrdf_cli.sh: render.json: bp.brdf shaded from the vectors, equal to blinn in float"""
    argv = ["check_json", *args]
    d = load(argv[1])
    sc = [s for s in d["scenes"] if s["scene"] == "teapot"][0]
    m = {x["model"]: x for x in sc["models"]}
    bp = m["bp"]
    assert bp["shading"] == "full-brdf", bp["shading"]
    assert bp["reference"] == "blinn", bp["reference"]
    # float against float: a few units of 2^-24 of the peak (identical in exact arithmetic)
    peak = bp["metrics"]["peak_reference"]
    assert peak > 0.1, peak
    assert bp["metrics"]["max_abs"] <= 1e-4 * peak, (bp["metrics"]["max_abs"], peak)
    assert bp["double_reference_check"]["max_abs_specular_difference"] <= 1e-3 * peak, bp["double_reference_check"]


@check
def fullbrdf_cli_physical_user_measured_rows(*args):
    """check_json of test_fullbrdf_cli.sh: physical.json: the user and measured rows"""
    argv = ["check_json", *args]
    d = load(argv[1])
    rows = {r["model"]: r for r in d["cost"]["rows"]}
    for name, kind in (("bp", "user BRDF (N, L, V)"), ("merl:b64", "table lookup")):
        r = rows[name]
        assert r["evaluates"] == kind, (name, r["evaluates"])
        assert r["status"] == "ok", (name, r["status"], r["check_max_abs_of_peak"])
        assert r["evaluations_per_s"] is not None and math.isfinite(r["evaluations_per_s"]) \
            and r["evaluations_per_s"] > 0, (name, r["evaluations_per_s"])
    for r in rows.values():
        assert r["status"] == "ok", (r["model"], r["check_max_abs_of_peak"])
    assert "memory bandwidth" in d["lookup_note"]


@check
def fullbrdf_cli_render_measured_material_beside_fits(*args):
    """check_json of test_fullbrdf_cli.sh: render.json: the measured material beside its fits"""
    argv = ["check_json", *args]
    d = load(argv[1])
    sc = [s for s in d["scenes"] if s["scene"] == "teapot"][0]
    m = sc["measured"][0]
    assert m["material"] == "b64" and m["check_status"] == "ok", m
    peak = m["peak_radiance"]
    assert peak > 0.5, peak
    fits = {f["fit"]: f for f in m["fits"]}
    assert sorted(fits) == ["blinn-phong fit", "ct-beckmann fit", "ct-ggx fit"], sorted(fits)
    b = fits["blinn-phong fit"]
    for key, want in (("n", 64), ("ks", 2.5), ("kd", 0.08)):
        assert abs(b[key] - want) <= 1e-3 * want, (key, b[key], want)
    assert b["rms"] <= 0.01 * peak and b["max_abs"] <= 0.1 * peak, (b["rms"], b["max_abs"], peak)


# ---- test_machine_readable.sh ------------------------------------------------------------------

@check
def machine_readable_csv_headers_as_documented(*args):
    """test_machine_readable.sh: a CSV header differs from docs/csv-columns.md"""
    import collections, csv, re, sys
    argv = ["-", *args]
    doc = collections.OrderedDict()
    for line in open(argv[1]):
        m = re.match(r"^\| (\w+\.csv) \| (\w+) \|", line)
        if m:
            doc.setdefault(m.group(1), []).append(m.group(2))
    assert set(doc) == {"accuracy.csv", "throughput.csv", "frontier.csv", "compare.csv"}, list(doc)
    for name, cols in doc.items():
        header = next(csv.reader(open(f"{argv[2]}/{name}")))
        assert header == cols, (name, header, cols)
        for c in header:
            assert not re.search(r"(^|_)(max_rel|at_x)$", c) and not c.startswith("rate_"), (name, c, "unit missing")


# ---- test_rusticl.sh ---------------------------------------------------------------------------

@check
def rusticl_figures_against_pocl(*args):
    """test_rusticl.sh: rusticl's figures against PoCL's"""
    import json, sys
    argv = ["-", *args]
    a, b = (json.load(open(p)) for p in argv[1:3])
    assert "llvmpipe" in b["context"]["device"], b["context"]["device"]
    assert len(a["results"]) == len(b["results"]) == 2
    for ra, rb in zip(a["results"], b["results"]):
        assert ra["label"] == rb["label"]
        if rb.get("status") == "device_disagrees":
            print("%s flagged device_disagrees on rusticl" % rb["label"])
            continue
        for zone in ("epicentre", "attenuation", "whole"):
            for k, x in ra[zone].items():
                y = rb[zone][k]
                if isinstance(x, float) and k.startswith("max"):
                    assert "%.3e" % x == "%.3e" % y, (ra["label"], zone, k, x, y)
        assert rb["timing"]["timer"] in ("profiling events", "wall time: the driver's profiling events gave no time")


@check
def rusticl_throughput_on_rusticl_every_row(*args):
    """check_json of test_rusticl.sh: throughput on rusticl: every row measured, the scalar kernels"""
    argv = ["check_json", *args]
    d = load(argv[1])
    assert "llvmpipe" in d["context"]["device"]
    assert all(r["status"] == "ok" for r in d["results"]), [r for r in d["results"] if r["status"] != "ok"]
    assert len(d["results"]) == 3 * 2
    assert "-DTP_W=1" in d["builds"][0]["build_options"], d["builds"]


@check
def rusticl_device_all_three_devices(*args):
    """check_json of test_rusticl.sh: --device all: three devices, each with its own context"""
    argv = ["check_json", *args]
    d = load(argv[1])
    devs = d["context"]["devices"]
    assert len(devs) == 3, devs
    assert any("llvmpipe" in x["device"] for x in devs) and any("basic" in x["device"] for x in devs), devs
    assert len({r["device"] for r in d["results"]}) == 3


@check
def rusticl_compare_three_drivers(*args):
    """check_json of test_rusticl.sh: compare lays the three drivers side by side"""
    argv = ["check_json", *args]
    d = load(argv[1])
    assert len(d["runs"]) == 3, [r["name"] for r in d["runs"]]


# ---- test_shaderlang_cli.sh --------------------------------------------------------------------

@check
def shaderlang_cli_five_writings_lyon_k2(*args):
    """check_json of test_shaderlang_cli.sh: the five writings have lyon:k=2's figures in accuracy.json"""
    argv = ["check_json", *args]
    d = load(argv[1])
    r = {x["label"]: x for x in d["results"]}
    ref = r["lyon:k=2"]
    for label in ("quartic_cl:k=0.25", "quartic_glsl:k=0.25", "quartic_hlsl:k=0.25", "q4"):
        x = r[label]
        assert x["status"] == "ok", x
        for zone, key in (("epicentre", "max_rel"), ("attenuation", "max_abs"), ("whole", "max_abs")):
            a, b = x[zone][key], ref[zone][key]
            assert abs(a - b) <= 1e-12 * abs(b), (label, zone, a, b)
            assert x[zone]["at_n"] == ref[zone]["at_n"], (label, zone)


@check
def shaderlang_cli_brdf_blinn_phong_cook_torrance(*args):
    """check_json of test_shaderlang_cli.sh: .brdf Blinn-Phong and Cook-Torrance are the built-in models"""
    argv = ["check_json", *args]
    d = load(argv[1])
    r = {x["model"]: x for x in d["results"]}
    bp, ct = r["blinnphong"], r["ct_ggx"]
    full = r["ct_full"]
    assert full["reference"] == "ct-ggx:F0=0.5", full["reference"]
    for zone, key in (("epicentre", "max_rel"), ("attenuation", "max_abs"), ("whole", "max_abs")):
        assert full[zone][key] < 1e-9, (zone, full[zone])
    assert bp["reference"] == "blinn" and ct["reference"] == "ct-ggx:F0=0.5", (bp["reference"], ct["reference"])
    assert bp["epicentre"]["max_rel"] < 1e-9, bp["epicentre"]
    for zone, key in (("epicentre", "max_rel"), ("attenuation", "max_abs"), ("whole", "max_abs")):
        assert ct[zone][key] < 1e-9, (zone, ct[zone])
    assert abs(bp["whole"]["max_abs"] - 0.5) < 1e-9 and bp["whole"]["at_n"] == 2, bp["whole"]
    assert abs(bp["whole"]["at_x"] - math.pi / 4) < 1e-6, bp["whole"]


@check
def shaderlang_cli_brdf_model_measured_by_throughput(*args):
    """check_json of test_shaderlang_cli.sh: the .brdf model measured by throughput"""
    argv = ["check_json", *args]
    d = load(argv[1])
    assert [x for x in d["results"] if x["model"] == "blinnphong"], [x["model"] for x in d["results"]]


# ---- test_usermodel.sh -------------------------------------------------------------------------

@check
def usermodel_closed_form_figures_k_c_n(*args):
    """check_json of test_usermodel.sh: closed-form figures of k c^n (k = 3 and 0.5)"""
    argv = ["check_json", *args]
    d = load(argv[1])
    r = {x["label"]: x for x in d["results"]}
    assert set(r) == {"scaled:k=3", "half"}, list(r)
    for label, k in (("scaled:k=3", 3.0), ("half", 0.5)):
        x = r[label]
        assert x["status"] == "ok", x
        assert x["reference"] == "phong"
        assert abs(x["epicentre"]["max_rel"] - abs(k - 1)) < 1e-12, x["epicentre"]
        assert abs(x["whole"]["max_abs"] - abs(k - 1)) < 1e-12, x["whole"]
        assert abs(x["whole"]["at_x"]) < 1e-9, x["whole"]
        assert abs(x["attenuation"]["max_abs"] - abs(k - 1) * math.exp(-0.511)) < 1e-12, x["attenuation"]
        # The double reference ran on the device: its check against the float sweep holds.
        assert x["check"]["in_4th_digit_units"] < 0.05, x["check"]
        assert x["check"]["probe_max_diff_of_peak"] < 1e-5, x["check"]
        assert "reason" not in x, x
    assert r["scaled:k=3"]["params"] == {"k": 3}


@check
def usermodel_myquad_cq2_closed_form(*args):
    """check_json of test_usermodel.sh: myquad:a=0.5,b=0 has cq2's closed-form maximum"""
    argv = ["check_json", *args]
    d = load(argv[1])
    x = d["results"][0]
    assert x["label"] == "myquad:a=0.5,b=0" and x["params"] == {"a": 0.5, "b": 0}, x
    u = -math.expm1(-0.511 / 50)
    expect = 1 - (1 - 50 * u / 2) ** 2 / math.exp(-0.511)
    assert abs(x["epicentre"]["max_rel"] - expect) < 1e-12, (x["epicentre"], expect)
    assert x["epicentre"]["at_n"] == 50


@check
def usermodel_only_user_model_runs(*args):
    """check_json of test_usermodel.sh: only the user model runs when no --models is given"""
    argv = ["check_json", *args]
    d = load(argv[1])
    assert [x["model"] for x in d["results"]] == ["cube"], d["results"]


@check
def usermodel_float_fallback_reported_accuracy(*args):
    """check_json of test_usermodel.sh: float fallback is reported in accuracy.json"""
    argv = ["check_json", *args]
    d = load(argv[1])
    x = d["results"][0]
    assert "no cl_khr_fp64" in x["reason"], x
    assert abs(x["epicentre"]["max_rel"] - 0.5) < 1e-6, x["epicentre"]


@check
def usermodel_nan_values_counted(*args):
    """check_json of test_usermodel.sh: NaN values are counted, with the first location"""
    argv = ["check_json", *args]
    d = load(argv[1])
    x = d["results"][0]
    S = 256
    expect, slack = 0, 0
    for n in range(2, 13):
        se = -math.expm1(-0.511 / n)
        for j in range(1, S + 1):
            sj = se * (1 / se) ** (j / S)
            if abs(sj - 0.5) < 1e-6: slack += 1
            elif sj > 0.5: expect += 1
    assert x["status"] == "invalid_values", x["status"]
    cnt = x["invalid"]["count"]
    assert expect <= cnt <= expect + slack, (cnt, expect, slack)
    assert x["invalid"]["at_n"] == 2 and x["invalid"]["at_x"] > math.pi / 3 - 1e-6, x["invalid"]
    assert str(cnt) in x["reason"] and "NaN, Inf or negative" in x["reason"], x["reason"]


@check
def usermodel_gates_on_closed_forms(*args):
    """check_json of test_usermodel.sh: user-model gates judged on closed forms"""
    argv = ["check_json", *args]
    d = load(argv[1])
    g = d["gates"]
    assert [x["status"] for x in g] == ["pass", "fail", "pass"], [(x["status"], x.get("reason")) for x in g]
    assert all(x["user_model"] for x in g)
    assert abs(g[0]["measured"] - 0.5) < 1e-12 and abs(g[1]["measured"] - 0.5) < 1e-12
    assert abs(g[2]["measured"] - 0.75) < 1e-12
    assert d["summary"]["sweeps"] == 2, d["summary"]


@check
def usermodel_render_k_c_n_identity(*args):
    """check_json of test_usermodel.sh: render of k c^n: identity figures"""
    argv = ["check_json", *args]
    d = load(argv[1])
    ms = {m["model"]: m for m in d["scenes"][0]["models"]}
    one, two = ms["scaled:k=1"], ms["scaled:k=2"]
    assert one["family"] == "user" and one["reference"] == "phong"
    assert one["metrics"]["max_abs"] == 0, one["metrics"]
    p = two["metrics"]["peak_reference"]
    assert p > 0 and abs(two["metrics"]["max_abs"] - p) <= 1e-6 * p, two["metrics"]
    assert one["double_reference_check"]["within_bound"] and two["double_reference_check"]["within_bound"]


@check
def usermodel_frontier_all_models_with_user(*args):
    """check_json of test_usermodel.sh: the frontier of all --models with a user model"""
    argv = ["check_json", *args]
    d = load(argv[1])
    assert [m["model"] for m in d["models"]] == ["fq2", "scaled:k=2"], [m["model"] for m in d["models"]]


@check
def usermodel_user_model_error_field(*args):
    """check_json of test_usermodel.sh: the user model's error field"""
    argv = ["check_json", *args]
    d = load(argv[1])
    assert d["model"] == "scaled:k=2" and d["reference"] == "phong"
    assert d["check"]["max_rel_diff"] < 1e-6, d["check"]
    # (2r - r) / r = 1 in every cell, and exactly so in float (2r and 2r - r are exact)
    cells = d["grid"]["rows"] * d["grid"]["cols"]
    assert len(d["epicentre_rel"]) == cells and all(v == 1 for v in d["epicentre_rel"]), d["epicentre_rel"][:8]


@check
def usermodel_user_model_measured_by_throughput(*args):
    """check_json of test_usermodel.sh: the user model measured by throughput"""
    argv = ["check_json", *args]
    d = load(argv[1])
    r = [x for x in d["results"] if x["model"] == "myquad"]
    assert len(r) == 1, [x["model"] for x in d["results"]]
    r = r[0]
    assert r["status"] == "ok", r
    # the ratio to pow() is this median over the median of the pow() row, measured in the same run
    p = [x for x in d["results"] if x["label"] == "pow" and x["n_mode"] == r["n_mode"] and x["variant"] == r["variant"]][0]
    assert abs(r["ratio_to_reference"] - r["evals_per_s"]["median"] / p["evals_per_s"]["median"]) <= 1e-9 * r["ratio_to_reference"], r
    assert r["accuracy"]["status"] == "ok" and r["accuracy"]["max_diff_of_peak"] < 1e-5, r["accuracy"]


@check
def usermodel_doc_example_figures(*args):
    """test_usermodel.sh: the doc's example gives other figures than the doc states"""
    import json, math, re, sys
    argv = ["-", *args]
    d = json.load(open(argv[1]))
    doc = open(argv[2]).read()
    sq, quad = d["results"]
    for zone, key in (("epicentre", "max_rel"), ("attenuation", "max_abs"), ("whole", "max_abs")):
        a, b = sq[zone], quad[zone]
        assert abs(a[key] - b[key]) <= 1e-12 * b[key] and a["at_n"] == b["at_n"], (zone, a, b)
    def f(c, n):
        b = max(0.45 * n * (c - 1) + 1, 0.0)
        return b * b
    def xe(n): return math.acos(math.exp(-0.511 / n))
    def maximum(g, lo, hi, steps=4000):
        xs = [lo + (hi - lo) * i / steps for i in range(steps + 1)]
        i = max(range(len(xs)), key=lambda k: g(xs[k]))
        a, b = xs[max(i - 1, 0)], xs[min(i + 1, steps)]
        r = (math.sqrt(5) - 1) / 2
        for _ in range(100):
            x1, x2 = b - r * (b - a), a + r * (b - a)
            if g(x1) > g(x2): b = x2
            else: a = x1
        return max(g(xs[i]), g((a + b) / 2))
    rel = lambda n: maximum(lambda x: abs(f(math.cos(x), n) / math.cos(x) ** n - 1), 0.0, xe(n))
    ab = lambda n: maximum(lambda x: abs(f(math.cos(x), n) - math.cos(x) ** n), xe(n), math.pi / 2, 40000)
    e, t = sq["epicentre"], sq["attenuation"]
    assert e["at_n"] == 16 and t["at_n"] == 1000, (e, t)
    assert abs(e["max_rel"] - rel(16)) < 1e-9, (e, rel(16))
    assert abs(t["max_abs"] - ab(1000)) < 1e-9, (t, ab(1000))
    # the maxima over n are where the run puts them (a sample of the grid)
    for n in (17, 20, 32, 64, 100, 250, 500, 999):
        assert rel(n) <= e["max_rel"] + 1e-12 and ab(n) <= t["max_abs"] + 1e-12, n
    # the doc states them to 4 significant digits
    m = re.search(r"max δ of ([0-9.]+)% in the epicentre \(at n = (\d+), x = ([0-9.]+) rad\) and a max Δ of\s+([0-9.]+) in the attenuation zone \(at n = (\d+), x = ([0-9.]+) rad\)", doc)
    assert m, "no figures in the doc"
    assert m.group(1) == "%.4g" % (100 * e["max_rel"]) and int(m.group(2)) == 16, (m.groups(), e)
    assert float(m.group(3)) == round(e["at_x"], 4), (m.groups(), e)
    assert m.group(4) == "%.4f" % t["max_abs"] and int(m.group(5)) == 1000, (m.groups(), t)
    assert float(m.group(6)) == round(t["at_x"], 4), (m.groups(), t)


@check
def usermodel_native_powr_exact_reference(*args):
    """check_json of test_usermodel.sh: native_powr is exact in the reference"""
    argv = ["check_json", *args]
    d = load(argv[1])
    x = d["results"][0]
    assert x["status"] == "ok", x
    assert x["epicentre"]["max_rel"] < 1e-13 and x["whole"]["max_abs"] < 1e-13, x


def main(argv):
    if len(argv) == 2 and argv[1] == "--list":
        print("\n".join(sorted(CHECKS)))
        return 0
    if len(argv) < 2 or argv[1] not in CHECKS:
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
