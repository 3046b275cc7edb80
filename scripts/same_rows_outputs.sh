#!/bin/bash
# same_rows_outputs.sh - do `rows` and `compare` say the same before and after the files carried
# their rows? One small run of throughput, render, fit and frontier by the NEW binary; the same
# files as the previous version wrote them (the "rows" member taken out, the previous schema
# string); then OLD_BINARY reads the latter and NEW_BINARY the former: `rows` in markdown, CSV
# and JSON for each file, and `compare` of the run with itself, must be identical but for the
# schema strings and the folders' names. Also OLD_BINARY and NEW_BINARY on the previous-version
# files alone (the upgrade path against the old readers).
# usage: scripts/same_rows_outputs.sh OLD_BINARY NEW_BINARY
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 OLD_BINARY NEW_BINARY" >&2; exit 2; }
old=$1 new=$2
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
cd "$out"
mkdir next prev   # names of one length: the text tables align alike
"$new" throughput --models fq2,cq2 --variants default --n-modes uniform,varying --no-sweep --no-host-c --reps 5 \
    --min-time 0.001 --json next/throughput.json >/dev/null 2>&1
"$new" render --scene spheres --models phong,fq2,cq2 --size 64x32 --time-sizes 64x32 --reps 3 --warmup 0 \
    --json next/render.json >/dev/null 2>&1
"$new" fit --n-min 2 --n-max 20 --samples 64 --json next/fit.json --quiet >/dev/null 2>&1
"$new" frontier --models phong,fq2,cq2 --samples 64 --reps 1 --rounds 1 --no-image --json next/frontier.json >/dev/null 2>&1
python3 - <<'PY'
import json
prev = {"throughput": "brdfbench.throughput/3", "render": "brdfbench.render/1", "fit": "brdfbench.fit/1",
        "frontier": "brdfbench.frontier/1"}
for k, s in prev.items():
    d = json.load(open("next/%s.json" % k))
    del d["rows"]
    d["schema"] = s
    json.dump(d, open("prev/%s.json" % k, "w"))
PY
norm() { sed -e 's#brdfbench\.[a-z]*/[0-9]*#SCHEMA#g' -e 's#"date": "[^"]*"#DATE#' -e 's#\bprev\b#RUN#g; s#\bnext\b#RUN#g'; }
diffs=0 checks=0
for k in throughput render fit frontier; do
    for fmt in md csv json; do
        "$old" rows "prev/$k.json" --format "$fmt" | norm >a
        "$new" rows "next/$k.json" --format "$fmt" | norm >b
        checks=$((checks + 1))
        cmp -s a b || { diffs=$((diffs + 1)); echo "rows $k --format $fmt differs:"; diff a b | head -6; }
        "$new" rows "prev/$k.json" --format "$fmt" | norm >c
        checks=$((checks + 1))
        cmp -s a c || { diffs=$((diffs + 1)); echo "rows $k --format $fmt (previous version's file) differs:"; diff a c | head -6; }
    done
done
"$old" compare prev prev --json - 2>/dev/null | norm >a
"$new" compare next next --json - 2>/dev/null | norm >b
checks=$((checks + 1))
cmp -s a b || { diffs=$((diffs + 1)); echo "compare --json differs:"; diff a b | head -6; }
"$old" compare prev prev --out cmp_old 2>/dev/null | grep -v '^written:' | norm >a
"$new" compare next next --out cmp_new 2>/dev/null | grep -v '^written:' | norm >b
checks=$((checks + 1))
cmp -s a b || { diffs=$((diffs + 1)); echo "compare (text) differs:"; diff a b | head -6; }
echo "$checks outputs compared, $diffs differ"
[ "$diffs" -eq 0 ]
