#!/usr/bin/env bash
# test_machine_readable.sh - one --samples range for every command (or the reason for a smaller
# one, in its --help), and --json - (the document alone on standard output) on every command
# that writes a document.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
cd "$T" || exit 1

# 1. --samples: every command that takes it accepts [16, 4194304] (the accuracy sweep's
#    ACC_MAX_SAMPLES, 2^22), or its --help entry states why it takes less ("since ...").
COMMANDS=$("$BIN" --help | awk '/^  [a-z]/ { print $1 }' | tr '\n' ' ')
for c in $COMMANDS; do
    "$BIN" "$c" --help >"$T/help_$c" 2>&1
    # the entry with its continuation lines (indented 21 columns) joined
    entry=$(python3 -c '
import re, sys
lines, out = open(sys.argv[1]).read().split("\n"), []
for i, l in enumerate(lines):
    if l.startswith("  --samples "):
        out = [l] + [m for m in __import__("itertools").takewhile(lambda m: m.startswith(" " * 21), lines[i + 1:])]
print(" ".join(x.strip() for x in out))' "$T/help_$c")
    [ -n "$entry" ] || continue
    hi=$(printf '%s' "$entry" | grep -oE 'in \[16, [0-9]+\]' | grep -oE '[0-9]+\]' | tr -d ']')
    if [ "$hi" = 4194304 ] || printf '%s' "$entry" | grep -qE 'since|because'; then ok
    else bad "$c --samples: maximum $hi differs from 4194304 with no reason: $entry"; fi
done

# The rest needs an OpenCL device.
if ! "$BIN" list --json - | python3 -c 'import json,sys; d=json.load(sys.stdin); sys.exit(0 if any(p["devices"] for p in d["platforms"]) else 1)'; then
    echo "$pass passed, $fail failed; SKIP: no OpenCL device for the checks that run kernels"
    [ "$fail" -eq 0 ] && exit 77 || exit 1
fi

# 2. --json -: standard output holds the one document (json.load of all of it: any table or
#    "written:" line beside it fails the parse), of the command's schema; no run folder is
#    made (no results/), and the temporary folder the run wrote into is gone (TMPDIR empty),
#    sub-folders included (render/<scene>/, frontier_teapot/).
mkdir -p "$T/tmp"
json_alone() {   # json_alone WHAT SCHEMA ARGS...
    local what=$1 schema=$2
    shift 2
    TMPDIR="$T/tmp" "$BIN" "$@" --json - >"$T/doc.json" 2>"$T/err"
    local rc=$?
    [ $rc -eq 0 ] || { bad "$what --json -: exit $rc: $(tail -c 400 "$T/err")"; return; }
    python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["schema"] == sys.argv[2], d["schema"]' \
        "$T/doc.json" "$schema" && ok || bad "$what --json -: stdout is not the $schema document alone: $(head -c 300 "$T/doc.json")"
    [ ! -e results ] && ok || bad "$what --json - without --out made results/"
    [ -z "$(ls -A "$T/tmp")" ] && ok || bad "$what --json - left its temporary folder: $(ls -AR "$T/tmp" | head -5)"
    cp "$T/doc.json" "$T/$what.json"
}
json_alone render brdfbench.render/3 render --scene spheres --models phong,fq2 --size 64x32 --time-sizes none --reps 1 --warmup 0
json_alone frontier brdfbench.frontier/3 frontier --models phong,fq2 --samples 64 --reps 1 --rounds 1 --no-image
json_alone reproduce brdfbench.claims/2 reproduce --samples 64 --no-grid-check --q-step 0.1 --q-samples 64 --q-n-step 50 --no-energy
"$BIN" accuracy --models fq2,cq2 --n-min 2 --n-max 6 --samples 16 --json "$T/acc.json" --csv "$T/accuracy.csv" >/dev/null 2>&1
json_alone compare brdfbench.compare/1 compare "$T/acc.json" "$T/acc.json"

# 3. CSV headers: each file's header is, column for column, the documented table of
#    docs/csv-columns.md (the table is the reference: a renamed or added column fails here);
#    units in the names: no bare max_rel or at_x (a fraction and radians said by the name).
#    accuracy.csv is the --csv of the accuracy run above; frontier.csv that of an all --quick run
#    (its frontier step writes the file as frontier does), which also gives section 4 the
#    documents only all writes (measured.json with a synthetic MERL material, field_fq2.json,
#    plots.json) and q_sweep.json; compare.csv that of section 5's compare.
"$BIN" throughput --models fq2 --variants default --n-modes uniform --no-sweep --no-host-c --reps 1 --min-time 0.001 \
    --csv "$T/throughput.csv" --json "$T/throughput.json" >/dev/null 2>&1
"${MERL_SYNTH:?MERL_SYNTH must name the merl_synth writer}" "$T/m.binary" blinn 64 2.5 0.08 >/dev/null
"$BIN" all --quick --models fq2 --measured "$T/m.binary" --out "$T/allq" --quiet >/dev/null 2>&1
cp "$T/allq/frontier.csv" "$T/frontier.csv" 2>/dev/null
"$BIN" compare "$T/acc.json" "$T/acc.json" --out "$T/cmpacc" >"$T/cmpacc.out" 2>"$T/cmpacc.err"
cp "$T/cmpacc/compare.csv" "$T/compare.csv" 2>/dev/null
jsoncheck machine_readable_csv_headers_as_documented "$SRC/docs/csv-columns.md" "$T" && ok || bad "a CSV header differs from docs/csv-columns.md"

# 4. JSON Schemas (docs/schemas/, draft 2020-12): each is a valid schema, named after its kind;
#    every schema string of host/output/schemas.h (but the older versions kept for the readers)
#    has its file; the documents of the small runs here validate against the schema their
#    "schema" string names; a broken copy of each (a required member taken out, an x past pi/2,
#    a boolean made a string, a status outside its enum, a null without its reason) fails.
"$BIN" list --json "$T/list.json" >/dev/null 2>&1
"$BIN" fit --n-min 2 --n-max 6 --samples 16 --json "$T/fit.json" --quiet >/dev/null 2>&1
"$BIN" fit --family gauss --n-min 2 --n-max 6 --samples 16 --json "$T/fitfam.json" --quiet >/dev/null 2>&1
# a gates file with a gate that passes and one that fails (measured Delta > 0 > 1e-9): gate exits 1
cat >"$T/gates.json" <<'JSON'
{"schema": "brdfbench.gates/1", "gates": [
  {"model": "fq2", "metric": "epicentre.max_rel", "n_min": 2, "n_max": 6, "samples": 16, "max": 1},
  {"model": "fq2", "metric": "attenuation.max_abs", "n_min": 2, "n_max": 6, "samples": 16, "max": 1e-9}]}
JSON
"$BIN" gate "$T/gates.json" --json "$T/gate.json" --quiet >/dev/null 2>&1
# measured.json, field_fq2.json, plots.json and q_sweep.json: the all --quick run of section 3
# (energy.json and physical.json, which only reproduce's energy checks write, are validated
# where test_reproduce_cli.sh makes them)
cp "$T/allq/q_sweep.json" "$T/q_sweep.json" 2>/dev/null
cp "$T/allq/measured.json" "$T/measured.json" 2>/dev/null
cp "$T/allq/field_fq2.json" "$T/field.json" 2>/dev/null
cp "$T/allq/plots.json" "$T/plots.json" 2>/dev/null
"$BIN" rows "$T/throughput.json" --format json --output "$T/rows.json" >/dev/null 2>&1
jsoncheck schemas_cover "$SRC/host/output/schemas.h" "$SRC/docs/schemas" && ok || bad "a schema string of schemas.h has no file in docs/schemas/"
DOCS="acc throughput render frontier reproduce compare list fit fitfam gate gates q_sweep measured field plots rows"
for n in $DOCS; do
    jsoncheck schema_docs "$SRC/docs/schemas" "$T/$n.json" && ok || bad "$n.json does not validate against its schema"
done
jsoncheck schema_broken "$SRC/docs/schemas" "$T" $DOCS && ok || bad "a broken document validates against its schema"

# 5. compare of two accuracy runs (no rate in them) draws its own chart: compare.png is there,
#    a PNG (its 8-byte signature), and every file the "written:" line names exists.
#    (the compare of section 3)
[ "$(head -c 8 "$T/cmpacc/compare.png" 2>/dev/null | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] && ok \
    || bad "compare of two accuracy runs wrote no compare.png: $(ls "$T/cmpacc")"
written=$(sed -n "s|^written: $T/cmpacc/||p" "$T/cmpacc.out")
[ -n "$written" ] && ok || bad "compare printed no written: line: $(cat "$T/cmpacc.out" | tail -2)"
for f in $(printf '%s' "$written" | tr ',' ' '); do
    [ -e "$T/cmpacc/$f" ] && ok || bad "compare says it wrote $f, which is not there"
done

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
