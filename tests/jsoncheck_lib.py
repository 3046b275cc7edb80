"""jsoncheck_lib.py - what the check modules of tests/jsoncheck.py share: the registry of named
checks (@check), strict JSON (load), has_context, load_result and read_csv."""
import csv
import json

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


def load_result(path, schema, keys):
    """A result file, loaded strictly, with its schema and context keys checked (has_context):
    the document and its context."""
    d = load(path)
    has_context(d, schema, keys)
    return d, d["context"]


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))
