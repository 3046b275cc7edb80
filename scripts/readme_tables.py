#!/usr/bin/env python3
"""readme_tables.py - README's figures regenerated from a run folder, never typed by hand.

    python3 scripts/readme_tables.py RUN_DIR                 print the blocks
    python3 scripts/readme_tables.py RUN_DIR --write README  replace them in README
    python3 scripts/readme_tables.py RUN_DIR --check README  exit 1 when README's differ

RUN_DIR holds accuracy.json (`brdfbench accuracy --models M1,M2,... --out RUN_DIR`, the grid
README states) and, for the claims block, claims.json (`brdfbench reproduce --out RUN_DIR`);
`brdfbench all` writes both. Each block sits in README between `<!-- figures:NAME -->` and
`<!-- /figures:NAME -->`:
  accuracy  the table of max delta (epicentre, with the n where it occurs) and max Delta
            (attenuation) per model, 4 significant digits, as the run reports them, and a line
            naming the run (grid, device, date, revision);
  claims    the line counting the claims' verdicts, with the run it came from.
A block whose file is missing from RUN_DIR is left as it is (--check: only the blocks present
are compared; --only NAME limits it to one). Timings are never regenerated into assertions:
they are quoted in README with the run they came from.
"""
import json
import os
import re
import sys

# How README names a model and writes its formula (presentation only; the figures come from
# the run). A label not listed here is shown as itself.
NAMES = {
    "cq2": ("cq2 (F2)", "(n/2·(c−1) + 1)²"),
    "fvol": ("fvol (paper 1)", "(0.463·n·(c−1) + 1)²"),
    "fvol64": ("fvol64", "(29/64·n·(c−1) + 1)²"),
    "schlick": ("schlick", "c / (n − n·c + c)"),
    "lyon:k=2": ("lyon, k = 2", "(1 − n(1−c)/4)⁴"),
    "fq:Q=0.64": ("fq, Q = 0.64 (paper 2)", "(k_Q(n)(c−1) + 1)²"),
    "fq2": ("fq2 (paper 2)", "((0.448n + 0.099)(c−1) + 1)²"),
}
QUAD_FORMULA = "((a·n + b)(c−1) + 1)²"


def sig4(v):
    """4 significant digits, trailing zeros kept (as %.4g drops them)."""
    if v == 0:
        return "0"
    s = "%.4g" % v
    digits = len(re.sub(r"[^0-9]", "", s.split("e")[0]).lstrip("0"))
    if "e" not in s and digits < 4:
        decimals = len(s.split(".")[1]) if "." in s else 0
        s = "%.*f" % (decimals + 4 - digits, v)
    return s


def run_line(doc, what):
    c = doc.get("context", {})
    parts = [what, "device: %s" % c.get("device", "?"), "date: %s" % c.get("date", "?")]
    rev = c.get("git_revision") or c.get("revision")
    if rev:
        parts.append("revision %s" % rev)
    return "; ".join(parts)


def accuracy_block(run):
    doc = json.load(open(os.path.join(run, "accuracy.json")))
    rows = [r for r in doc["results"] if r.get("status") == "ok"]
    out = ["| model | f(c, n) | max δ, epicentre | max Δ, attenuation |", "|---|---|---|---|"]
    grids = set()
    for r in rows:
        label = r["label"]
        name, formula = NAMES.get(label, (label, ""))
        if label.startswith("quad:"):
            name, formula = "**%s** (`brdfbench fit`)" % label, QUAD_FORMULA
        e, a = r["epicentre"], r["attenuation"]
        delta = "%s%% (n = %g)" % (sig4(100 * e["max_rel"]), e["at_n"])
        if label.startswith("quad:"):
            delta = "**%s**" % delta
        out.append("| %s | %s | %s | %s |" % (name, formula, delta, sig4(a["max_abs"])))
        grids.add((r.get("n_min"), r.get("n_max")))
    g = doc.get("context", {}).get("grid") or {}
    grid = "n step %g, %d samples per zone" % (g.get("n_step", float("nan")), g.get("samples_per_zone", 0))
    n_range = ", ".join("n ∈ [%g, %g]" % x for x in sorted(grids))
    out.append("")
    out.append("_From %s._" % run_line(doc, "`brdfbench accuracy` over %s, %s" % (n_range, grid)))
    return "\n".join(out)


def claims_block(run):
    doc = json.load(open(os.path.join(run, "claims.json")))
    s = doc["summary"]
    text = "%d rows: %d reproduced, %d not reproduced" % (s["rows"], s["reproduced"], s["not_reproduced"])
    if s.get("within_noise"):
        text += ", %d within noise" % s["within_noise"]
    return "%s (%s)." % (text, run_line(doc, "`brdfbench reproduce`"))


BLOCKS = {"accuracy": ("accuracy.json", accuracy_block), "claims": ("claims.json", claims_block)}


def main(argv):
    if len(argv) < 2:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    run, mode, readme, only = argv[1], None, None, None
    args = argv[2:]
    while args:
        a = args.pop(0)
        if a in ("--write", "--check") and args:
            mode, readme = a, args.pop(0)
        elif a == "--only" and args and args[0] in BLOCKS:
            only = args.pop(0)
        else:
            print("readme_tables.py: unknown argument %r (accepted: --write FILE, --check FILE, --only %s)"
                  % (a, "|".join(BLOCKS)), file=sys.stderr)
            return 2
    made = {}
    for name, (fname, fn) in BLOCKS.items():
        if (only is None or only == name) and os.path.exists(os.path.join(run, fname)):
            made[name] = fn(run)
    if not made:
        print("readme_tables.py: %s has none of %s" % (run, ", ".join(f for f, _ in BLOCKS.values())), file=sys.stderr)
        return 2
    if mode is None:
        for name, text in made.items():
            print("<!-- figures:%s -->\n%s\n<!-- /figures:%s -->\n" % (name, text, name))
        return 0
    doc = open(readme, encoding="utf-8").read()
    differ = []
    for name, text in made.items():
        pat = re.compile(r"(<!-- figures:%s -->\n)(.*?)(\n<!-- /figures:%s -->)" % (name, name), re.S)
        m = pat.search(doc)
        if not m:
            print("readme_tables.py: %s has no block <!-- figures:%s --> ... <!-- /figures:%s -->" % (readme, name, name),
                  file=sys.stderr)
            return 2
        if mode == "--check":
            # the figures, not the line naming the run (another run of the same grid gives the same figures)
            strip = lambda t: "\n".join(l for l in t.splitlines() if not l.startswith("_From "))
            have, want = strip(m.group(2)), strip(text)
            if have != want:
                differ.append(name)
                for h, w in zip(have.splitlines() + [""] * 99, want.splitlines()):
                    if h != w:
                        print("%s, block %s:\n  README: %s\n  run:    %s" % (readme, name, h, w))
        else:
            doc = doc[:m.start(2)] + text + doc[m.end(2):]
    if mode == "--write":
        tmp = readme + ".tmp"
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(doc)
        os.replace(tmp, readme)
        print("written: %s (%s)" % (readme, ", ".join(made)))
        return 0
    if differ:
        print("README's figures differ from the run's in: %s" % ", ".join(differ))
        return 1
    print("README's figures equal the run's (%s)" % ", ".join(made))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
