#!/usr/bin/env bash
# test_rows_primary.sh - throughput.json, accuracy.json, render.json, fit.json, frontier.json, energy.json and measured.json carry their
# rows (a "rows" member, built by the engine where it measures), and every reader reads them;
# files of the previous versions (written before the files carried rows) are read by their
# layout, so kept baselines still work.
#
# Where the expectations come from:
# - tests/rows_layouts.py maps each kind's own layout (results, scenes, compare, models: the
#   members docs/schemas/ describes) to rows a second time, in Python: the rows the program
#   reads, from a new file's rows member and from an old file's layout, must be those.
# - the same new file read twice, once through its rows member and once with the member taken
#   out and its schema set to the previous version (the upgrade function's path): the two
#   derivations are independent (one from the engine's memory, one from the file's detail) and
#   must give the same rows document, context lines included.
# - tests/fixtures/rows-v-previous/: a run of the version before rows (commit 099c3f9, and
#   48575e2 for accuracy.json: lobe rows, an fp16 row of half code, a hemisphere row; c0bc643 for
#   energy.json; 61a5e59 for measured.json, a material of tests/merl_synth; the
#   commands in its README.md); compare of it against a new run of the same commands pairs every
#   row (the row set of both is the layout mapping's).
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
cd "$T" || exit 1
LAYOUTS="$SRC/tests/rows_layouts.py"
OLD="$SRC/tests/fixtures/rows-v-previous"

# 1. an old run (previous schemas, no rows member) reads through the upgrade functions: rows
#    as the layout mapping says, the schema named as the file's
declare -A PREV=([throughput]=brdfbench.throughput/3 [render]=brdfbench.render/1 [fit]=brdfbench.fit/1
                 [frontier]=brdfbench.frontier/1 [accuracy]=brdfbench.accuracy/1 [energy]=brdfbench.energy/1
                 [measured]=brdfbench.measured/1)
declare -A NOW=([throughput]=brdfbench.throughput/5 [render]=brdfbench.render/3 [fit]=brdfbench.fit/3
                [frontier]=brdfbench.frontier/3 [accuracy]=brdfbench.accuracy/3 [energy]=brdfbench.energy/2
                [measured]=brdfbench.measured/2)
KINDS="throughput render fit frontier accuracy energy measured"
SYN=${MERL_SYNTH:?MERL_SYNTH must name the merl_synth writer}
for k in $KINDS; do
    python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if d["schema"] == sys.argv[2] and "rows" not in d else 1)' \
        "$OLD/$k.json" "${PREV[$k]}" && ok || bad "fixture $k.json is not a ${PREV[$k]} file without rows"
    "$BIN" rows "$OLD/$k.json" --format json --output "$T/old_$k.rows.json" 2>"$T/err" && ok || bad "rows $k (old): $(cat "$T/err")"
    python3 "$LAYOUTS" "$OLD/$k.json" "$T/old_$k.rows.json" && ok || bad "old $k.json: the upgrade's rows differ from its layout's"
done

# 2. a new run of the same commands: each file carries its rows under its new schema
mkdir -p new
"$BIN" throughput --models fq2 --variants default --n-modes uniform,varying --no-sweep --no-host-c --reps 3 \
    --min-time 0.001 --json new/throughput.json >/dev/null 2>"$T/err" || bad "throughput: $(cat "$T/err")"
"$BIN" render --scene spheres --models phong,fq2 --size 64x32 --time-sizes 64x32 --reps 3 --warmup 0 \
    --json new/render.json >/dev/null 2>"$T/err" || bad "render: $(cat "$T/err")"
"$BIN" fit --n-min 2 --n-max 6 --samples 16 --json new/fit.json --quiet >/dev/null 2>"$T/err" || bad "fit: $(cat "$T/err")"
"$BIN" frontier --models phong,fq2 --samples 64 --reps 1 --rounds 1 --no-image --json new/frontier.json \
    >/dev/null 2>"$T/err" || bad "frontier: $(cat "$T/err")"
# accuracy: lobe rows (phong, fq2), an fp16 row (half code) and a hemisphere row (ct-ggx)
"$BIN" accuracy --models phong,fq2,ct-ggx --model-file "$SRC/tests/test_shaderlang_files/phongapprox_half.hlsl" \
    --n-max 20 --samples 16 --hemisphere-grid 8x8x16 --axis-points 2 --json new/accuracy.json >/dev/null 2>"$T/err" \
    || bad "accuracy: $(cat "$T/err")"
# energy: reproduce's albedo and reciprocity checks (its other figures on coarse grids)
"$BIN" reproduce --out rep --samples 16 --no-grid-check --q-step 0.5 --q-samples 16 --q-n-step 499 --quiet \
    >/dev/null 2>"$T/err" && cp rep/energy.json new/energy.json || bad "reproduce (energy): $(cat "$T/err")"
# measured: the fixture's material again (a Blinn-Phong lobe, n = 64, ks = 2.5, kd = 0.08), the same name
"$SYN" m.binary blinn 64 2.5 0.08 >/dev/null || bad "merl_synth"
"$BIN" measured m.binary --fit-cells 2000 --json new/measured.json --quiet >/dev/null 2>"$T/err" \
    || bad "measured: $(cat "$T/err")"
python3 - new/accuracy.json <<'PY' && ok || bad "new accuracy.json: not lobe, fp16 and hemisphere rows"
import json, sys
rows = json.load(open(sys.argv[1]))["rows"]["rows"]
names = [{m["name"] for m in r["metrics"]} for r in rows]
assert len(rows) == 4 and "fp16.max_rel" in names[2] and "hemisphere.rms" in names[3], names
PY
for k in $KINDS; do
    python3 - "new/$k.json" "${NOW[$k]}" "${PREV[$k]}" "up_$k.json" <<'PY' && ok || bad "new $k.json: schema or rows member"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["schema"] == sys.argv[2], d["schema"]
rows = d["rows"]
assert set(rows) >= {"context", "disturbed_reps", "devices", "rows"} and rows["rows"], sorted(rows)
# the same file as the previous version wrote it: the rows member taken out
del d["rows"]
d["schema"] = sys.argv[3]
json.dump(d, open(sys.argv[4], "w"))
PY
    "$BIN" rows "new/$k.json" --format json --output "$T/new_$k.rows.json" 2>"$T/err" && ok || bad "rows $k: $(cat "$T/err")"
    "$BIN" rows "up_$k.json" --format json --output "$T/up_$k.rows.json" 2>"$T/err" && ok || bad "rows $k (upgrade): $(cat "$T/err")"
    # the rows member against the layout mapping, and against the upgrade function's reading
    python3 "$LAYOUTS" "new/$k.json" "$T/new_$k.rows.json" && ok || bad "new $k.json: its rows member differs from its layout's"
    python3 - "$T/new_$k.rows.json" "$T/up_$k.rows.json" "${NOW[$k]}" "${PREV[$k]}" <<'PY' && ok || bad "new $k.json: rows member and upgrade function read differently"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert a["source"]["schema"] == sys.argv[3] and b["source"]["schema"] == sys.argv[4], (a["source"], b["source"])
del a["source"]["schema"], b["source"]["schema"]
if a != b:
    for key in a:
        if a[key] != b[key]:
            print(key, json.dumps(a[key])[:300], "|", json.dumps(b[key])[:300], file=sys.stderr)
    sys.exit(1)
assert a["rows"] and all(r["metrics"] for r in a["rows"]), "no rows, or a row without metrics"
PY
done
# He's comparison (a mesh scene): its rows in the rows member as in the layout, and the same
# through the upgrade function
mkdir -p he
"$BIN" render --scene bunny --models phong,fq2 --size 64x32 --time-sizes 64x32 --reps 3 --warmup 0 \
    --json he/render.json >/dev/null 2>"$T/err" || bad "render bunny: $(cat "$T/err")"
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); del d["rows"]; d["schema"]="brdfbench.render/1"; json.dump(d, open(sys.argv[2], "w"))' \
    he/render.json he/up_render.json
"$BIN" rows he/render.json --format json --output "$T/he.rows.json" 2>"$T/err" && ok || bad "rows he: $(cat "$T/err")"
"$BIN" rows he/up_render.json --format json --output "$T/he_up.rows.json" 2>"$T/err" && ok || bad "rows he up: $(cat "$T/err")"
python3 "$LAYOUTS" he/render.json "$T/he.rows.json" && ok || bad "bunny render.json: its rows member differs from its layout's"
python3 - "$T/he.rows.json" "$T/he_up.rows.json" <<'PY' && ok || bad "bunny render.json: rows member and upgrade function read differently"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
del a["source"]["schema"], b["source"]["schema"]
assert a == b, [(x["row"], y["row"]) for x, y in zip(a["rows"], b["rows"]) if x != y][:3]
assert sum(r["attributes"].get("he") == "entry" for r in a["rows"]) >= 2, "no rows of He's comparison"
PY
# frontier.json of brdfbench.frontier/2 carried a rows member of its accuracy figures alone: such
# a file is read by its layout (the rows the page needs: rates, front, kind, source), never by
# that thinner member. The new file in /2's form (its rows member cut to /2's five figures, no
# texts, no attributes, no context lines) reads as the new file does.
python3 - new/frontier.json v2_frontier.json <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
d["schema"] = "brdfbench.frontier/2"
d["rows"]["context"] = {}
for r in d["rows"]["rows"]:
    r["metrics"], r["attributes"] = r["metrics"][:5], {}
    r.pop("texts", None)
json.dump(d, open(sys.argv[2], "w"))
PY
"$BIN" rows v2_frontier.json --format json --output "$T/v2_frontier.rows.json" 2>"$T/err" && ok || bad "rows frontier/2: $(cat "$T/err")"
python3 - "$T/new_frontier.rows.json" "$T/v2_frontier.rows.json" <<'PY' && ok || bad "frontier/2: not read by its layout"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert b["source"]["schema"] == "brdfbench.frontier/2", b["source"]
del a["source"]["schema"], b["source"]["schema"]
assert a == b, [k for k in a if a[k] != b[k]]
assert all(r["texts"]["source"] and "kind" in r["attributes"] for r in b["rows"]), "no source text or kind attribute"
PY

# rows not measured: a model whose values are NaN has its rows failed, with the reason, in the
# rows member as in the layout (status and reason are part of the mapping)
mkdir -p nan
"$BIN" throughput --model 'nanm=c*NAN' --models fq2,nanm --variants default --n-modes uniform --no-sweep --no-host-c \
    --reps 3 --min-time 0.001 --json nan/throughput.json >/dev/null 2>"$T/err" || bad "throughput nanm: $(cat "$T/err")"
"$BIN" frontier --model 'nanm=c*NAN' --models phong,nanm --samples 64 --reps 1 --rounds 1 --no-image \
    --json nan/frontier.json >/dev/null 2>"$T/err" || bad "frontier nanm: $(cat "$T/err")"
for k in throughput frontier; do
    "$BIN" rows "nan/$k.json" --format json --output "$T/nan_$k.rows.json" 2>"$T/err" && ok || bad "rows nan $k: $(cat "$T/err")"
    python3 "$LAYOUTS" "nan/$k.json" "$T/nan_$k.rows.json" && ok || bad "nan $k.json: rows member differs from its layout's"
    python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if any(r["status"] == "failed" and r["reason"] for r in d["rows"]) else 1)' \
        "$T/nan_$k.rows.json" && ok || bad "nan $k.json: no failed row with its reason"
    # the same file in the previous version's form: the upgrade function gives the same status
    python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); del d["rows"]; d["schema"]=sys.argv[3]; json.dump(d, open(sys.argv[2], "w"))' \
        "nan/$k.json" "nan/up_$k.json" "${PREV[$k]}"
    "$BIN" rows "nan/up_$k.json" --format json --output "$T/nan_up_$k.rows.json" 2>"$T/err" && ok || bad "rows nan up $k: $(cat "$T/err")"
    python3 "$LAYOUTS" "nan/up_$k.json" "$T/nan_up_$k.rows.json" && ok || bad "nan $k.json (previous form): upgrade differs from its layout's"
done

# the throughput page's record (throughput): the tuned C loop, two build options and the accuracy
# sweep in the rows member as in the layout mapping, and the same rows from the previous form
# (/3, no rows member) and from a /4 file, whose rows were written before they carried the page's
# record: both read by the layout
mkdir -p page
"$BIN" throughput --models phong,fq2 --variants default,fast-relaxed-math --n-modes uniform --reps 2 --min-time 0.001 \
    --work-items 64 --sweep-samples 16 --sweep-n-step 200 --sweep-reps 1 --json page/throughput.json >/dev/null \
    2>"$T/err" || bad "throughput page: $(cat "$T/err")"
python3 - page/throughput.json page/up3.json page/up4.json <<'PY' && ok || bad "page/throughput.json: no C rate, accuracy or sweep row"
import json, sys
d = json.load(open(sys.argv[1]))
rows = d["rows"]["rows"]
names = {m["name"] for r in rows for m in r["metrics"]}
assert {"host_c.evals_per_s", "accuracy.max_diff_of_peak", "device_points_per_s"} <= names, names
assert d["rows"]["texts"]["reps"] == "2", d["rows"].get("texts")
e = dict(d); del e["rows"]; e["schema"] = "brdfbench.throughput/3"
json.dump(e, open(sys.argv[2], "w"))
del d["rows"]["texts"]
for r in d["rows"]["rows"]:
    r["attributes"].pop("model_reference", None)
    r.pop("texts", None)
d["schema"] = "brdfbench.throughput/4"
json.dump(d, open(sys.argv[3], "w"))
PY
for f in throughput up3 up4; do
    "$BIN" rows "page/$f.json" --format json --output "$T/page_$f.rows.json" 2>"$T/err" && ok || bad "rows page $f: $(cat "$T/err")"
    python3 "$LAYOUTS" page/throughput.json "$T/page_$f.rows.json" && ok || bad "page $f: rows differ from the layout's"
done
for f in up3 up4; do
    python3 - "$T/page_throughput.rows.json" "$T/page_$f.rows.json" <<'PY' && ok || bad "page $f: read differently from the rows member"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
del a["source"]["schema"], b["source"]["schema"]
sys.exit(0 if a == b else 1)
PY
done

# the check bites: a value changed in the rows member is what the reader reports
python3 - new/throughput.json tampered.json <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
d["rows"]["rows"][1]["metrics"][0]["value"] *= 2
json.dump(d, open(sys.argv[2], "w"))
PY
"$BIN" rows tampered.json --format json --output "$T/tampered.rows.json" 2>/dev/null
python3 "$LAYOUTS" tampered.json "$T/tampered.rows.json" 2>/dev/null && bad "a changed rows member went unnoticed" || ok
# a new schema without its rows member is refused, naming the file and what is missing
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); del d["rows"]; json.dump(d, open(sys.argv[2], "w"))' \
    new/fit.json norows.json
expect 2 'norows.json: schema "brdfbench.fit/3" without its "rows"' rows norows.json

# 3. compare of the old run and the new run pairs every row (the metrics of the layout mapping)
"$BIN" compare "$OLD" new --json "$T/cmp.json" >/dev/null 2>"$T/err" && ok || bad "compare old new: $(cat "$T/err")"
python3 - "$T/cmp.json" "$LAYOUTS" "$OLD" <<'PY' && ok || bad "compare old new: rows not paired"
import json, os, sys
sys.path.insert(0, os.path.dirname(sys.argv[2]))
import rows_layouts
c = json.load(open(sys.argv[1]))
want = set()
for k in ("throughput", "render", "fit", "frontier", "accuracy", "energy", "measured"):
    for row, metrics in rows_layouts.expected(json.load(open(os.path.join(sys.argv[3], k + ".json")))).items():
        want |= {(k, row, m) for m in metrics if m != rows_layouts.STATUS}
got = {(r["kind"], r["key"], r["metric"]) for r in c["rows"]}
assert got == want, (sorted(want - got)[:5], sorted(got - want)[:5])
assert all(r["in_all_runs"] for r in c["rows"]), [r["key"] for r in c["rows"] if not r["in_all_runs"]][:5]
PY

# 4. compare's and rows' outputs are the same read through the rows members or the upgrade
#    functions: the same files compared with themselves both ways
mkdir -p up && for k in $KINDS; do cp "up_$k.json" "up/$k.json"; done
"$BIN" compare new new --json "$T/cmp_new.json" >/dev/null 2>&1
"$BIN" compare up up --json "$T/cmp_up.json" >/dev/null 2>&1
"$BIN" rows new >"$T/rows_new.md" 2>&1
"$BIN" rows up >"$T/rows_up.md" 2>&1
python3 - "$T/cmp_new.json" "$T/cmp_up.json" <<'PY' && ok || bad "compare reads the rows member and the upgrade differently"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for d in (a, b):
    d.pop("date", None)
    d.pop("runs", None)   # the folders' names and schemas
# the run's name is its folder's: the rest is the same
a_text = json.dumps(a).replace('"new"', '"RUN"')
b_text = json.dumps(b).replace('"up"', '"RUN"')
assert a_text == b_text and len(a["rows"]) > 30, "compare differs"
PY
# the markdown names each file's schema in its heading: the rest is the same
diff <(sed 's#brdfbench\.[a-z]*/[0-9]*#SCHEMA#g' "$T/rows_new.md") <(sed 's#brdfbench\.[a-z]*/[0-9]*#SCHEMA#g' "$T/rows_up.md") >/dev/null \
    && ok || bad "rows (markdown) reads the rows member and the upgrade differently"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
