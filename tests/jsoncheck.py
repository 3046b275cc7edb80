#!/usr/bin/env python3
"""jsoncheck.py - the shell tests' checks of the JSON (and CSV) files brdfbench writes, by name.

    python3 tests/jsoncheck.py CHECK FILE [ARGS...]

Runs the check function CHECK on FILE (and the further files or values in ARGS); exits 0 when
every assertion in it holds, else prints "FAIL CHECK FILE ARGS: what differed" (the assertion's
message and its file and line here) on stderr and exits 1. A check's expected values come from the test
(its arguments) or from a derivation written here, never from the program's output. JSON is
parsed strictly by load() (a NaN or Infinity literal fails it) unless a check says otherwise.
`python3 tests/jsoncheck.py --list` names the checks."""
import os
import sys
import traceback

from jsoncheck_lib import CHECKS, check, load, read_csv
import jsoncheck_cli  # noqa: F401  (registers its checks)
import jsoncheck_measure  # noqa: F401


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
    ("render", "no rows member", [("del", ["rows"])]),
    ("throughput", "a row's direction not in its enum", [("set", ["rows", "rows", 1, "metrics", 0, "direction"], "up")]),
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
    ("q_sweep", "no rows member", [("del", ["rows"])]),
    ("reproduce", "no rows member", [("del", ["rows"])]),
    ("physical", "no rows member", [("del", ["rows"])]),
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
    ("rows", "direction not in its enum", [("set", ["rows", 1, "metrics", 0, "direction"], "up")]),
    ("rows", "a failed row without its reason", [("set", ["rows", 1, "status"], "failed")]),
    ("rows", "no rows", [("del", ["rows"])]),
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
        here = [f for f in traceback.extract_tb(e.__traceback__)
                if os.path.dirname(f.filename) == os.path.dirname(__file__)]
        where = here[-1]
        what = f"{type(e).__name__}: {e}" if not isinstance(e, AssertionError) else (str(e) or "assertion")
        print(f"FAIL {name} {' '.join(args)}: {what} ({os.path.basename(where.filename)}:{where.lineno}: {where.line})"[:2000],
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
