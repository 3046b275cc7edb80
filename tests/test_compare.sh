#!/usr/bin/env bash
# test_compare.sh - `brdfbench compare` end to end. Expected values are worked out here from the
# input files (Python), never taken from compare's own output:
#   - a real throughput.json with every rate scaled by a known factor: that factor as the ratio
#     of every row, and "slower" wherever the scaled repetitions all fall below the original ones;
#   - a run against itself: ratio 1, "same" (p = 1) everywhere;
#   - two real runs: every row matched, ratio = median over median; the share of "same" is
#     printed, not asserted (timing on a shared machine is no test);
#   - rows in only some runs; accuracy changed/unchanged at the 4th significant digit with the
#     signed change; render and frontier files (synthetic, in their writers' layouts);
#   - every exit code: 0, 1 (--fail-if-slower, --fail-if-less-accurate), 2 (missing path, no
#     result file, another schema version, nothing in common, bad flags; nothing written), 3.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init

TP=(throughput --models cq2,fq2,phong --reps 5 --min-time 0.002 --work-items 8 --variants default --no-host-c
    --no-sweep --quiet)
"$BIN" "${TP[@]}" --out "$T/a" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "throughput run a: exit $rc: $(cat "$T/err")"
"$BIN" "${TP[@]}" --out "$T/a2" 2>"$T/err" && ok || bad "throughput run a2: $(cat "$T/err")"
"$BIN" accuracy --models cq2,fq2 --n-max 60 --samples 256 --out "$T/acc" >/dev/null 2>"$T/err" && ok ||
    bad "accuracy run: $(cat "$T/err")"

# ---- a known slowdown: every rate times f, f below the smallest min/max of any row ------------
python3 - "$T/a/throughput.json" "$T/slow" <<'PY' || bad "making the scaled run"
import json, os, sys
d = json.load(open(sys.argv[1]))
rows = [r for r in d["results"] if r["status"] == "ok"]
# half the smallest min/max ratio of any sample compare may decide on (absolute and normalised
# rates): every scaled repetition lies below every original one. A slower code scales them all.
REPS = ("evals_per_s_reps", "normalised_reps", "normalised_cpu_reps")
f = 0.5 * min(min(r[k]) / max(r[k]) for r in rows for k in REPS if r.get(k))
for r in d["results"]:
    for k in ("min", "median", "max"):
        if r["evals_per_s"][k] is not None:
            r["evals_per_s"][k] *= f
    for k in REPS:
        r[k] = [x * f for x in r.get(k, [])]
# the file edited in its layout, as the previous version wrote it (no "rows" member): read by
# that layout, so the edit is what compare sees
d.pop("rows", None)
d["schema"] = "brdfbench.throughput/3"
os.makedirs(sys.argv[2])
json.dump(d, open(os.path.join(sys.argv[2], "throughput.json"), "w"))
open(os.path.join(sys.argv[2], "factor"), "w").write(repr(f))
PY
"$BIN" compare "$T/a" "$T/slow" --out "$T/c1" >"$T/table" 2>"$T/err"
rc=$?
[ $rc -eq 0 ] && ok || bad "compare a slow: exit $rc: $(cat "$T/err")"
jsoncheck compare_scaled_run_factor_verdicts "$T/c1/compare.json" "$(cat "$T/slow/factor")" && ok || bad "scaled run: factor and verdicts"
grep -q "slower" "$T/table" && grep -q "cq2 | default | n uniform" "$T/table" && ok || bad "table lacks the rows: $(head -30 "$T/table")"
for f in compare.md compare.csv compare.json compare.png; do
    [ -s "$T/c1/$f" ] && ok || bad "$f not written"
done
head -c 8 "$T/c1/compare.png" | od -An -tx1 | grep -q "89 50 4e 47 0d 0a 1a 0a" && ok || bad "compare.png is not a PNG"
# CSV: one line per row and run, the ratio column as in the JSON
jsoncheck compare_csv_rows "$T/c1/compare.csv" && ok || bad "compare.csv"

# The slow run as a brdfbench.rows/1 document (brdfbench rows) carries all compare decides on:
# the same factor and verdicts as the throughput.json it was made from.
mkdir -p "$T/rows"   # the document named slow: the column's heading, as the folder's is
"$BIN" rows "$T/slow/throughput.json" --format json --output "$T/rows/slow" 2>"$T/err" && ok ||
    bad "rows --format json: $(cat "$T/err")"
"$BIN" compare "$T/a" "$T/rows/slow" --out "$T/c1r" --quiet 2>"$T/err" && ok || bad "compare a rows: $(cat "$T/err")"
jsoncheck compare_scaled_run_factor_verdicts "$T/c1r/compare.json" "$(cat "$T/slow/factor")" && ok ||
    bad "the rows document of the scaled run: factor and verdicts"
# rows --format csv: a header, then a line per metric: the peak's rate and one rate per result row
# (beside each rate, the row's accuracy: no rate)
"$BIN" rows "$T/a/throughput.json" --format csv --output "$T/rows.csv" 2>"$T/err" && ok || bad "rows csv: $(cat "$T/err")"
python3 - "$T/a/throughput.json" "$T/rows.csv" <<'PY' && ok || bad "rows.csv: not one line per rate"
import csv, json, sys
d = json.load(open(sys.argv[1]))
lines = [x for x in csv.DictReader(open(sys.argv[2], newline="")) if x["unit"] != "1"]
assert len(lines) == 1 + len(d["results"]), (len(lines), len(d["results"]))
for r, line in zip(d["results"], lines[1:]):
    assert line["label"] == r["label"] and line["variant"] == r["variant"] and line["n_mode"] == r["n_mode"], line
    assert line["metric"] == "evals_per_s" and line["unit"] == "1/s" and line["direction"] == "higher", line
    assert float(line["value"]) == r["evals_per_s"]["median"], (line["value"], r["evals_per_s"])
    assert int(line["reps"]) == len(r["evals_per_s_reps"]), line
PY
# rows --kind reads the one file it names: a broken file of another kind beside it is not read
mkdir -p "$T/rk" && cp "$T/a/throughput.json" "$T/rk/" && echo '{' >"$T/rk/accuracy.json"
"$BIN" rows "$T/rk" --kind throughput --format csv --output "$T/rk.csv" 2>"$T/err" && cmp -s "$T/rk.csv" "$T/rows.csv" &&
    ok || bad "rows --kind throughput beside a broken accuracy.json: $(cat "$T/err")"
"$BIN" rows "$T/rk" --output "$T/rk.md" 2>"$T/err"
[ $? -eq 2 ] && grep -q "rk/accuracy.json:2:1: " "$T/err" && ok || bad "rows of the whole folder: the broken file is not named: $(cat "$T/err")"
# --fail-if-slower: the factor is far below 0.5, so 40% fails and names the rows; 100% cannot
expect 1 "throughput cq2 \| default \| n uniform evals_per_s: 0\\.[0-9]+x the baseline" compare "$T/a" "$T/slow" --out "$T/c2" --fail-if-slower 40
"$BIN" compare "$T/a" "$T/slow" --out "$T/c3" --fail-if-slower 100 --quiet 2>"$T/err" && ok ||
    bad "--fail-if-slower 100 failed: $(cat "$T/err")"
# the other way round every row is faster and nothing fails
"$BIN" compare "$T/slow" "$T/a" --out "$T/c4" --fail-if-slower 0 --quiet 2>"$T/err" && ok ||
    bad "faster run failed --fail-if-slower 0: $(cat "$T/err")"
jsoncheck compare_reversed_faster "$T/c4/compare.json" && ok || bad "reversed: faster"

# ---- a run against itself --------------------------------------------------------------
"$BIN" compare "$T/a" "$T/a" --out "$T/self" --quiet --fail-if-slower 0 2>"$T/err" && ok ||
    bad "a against itself: $(cat "$T/err")"
jsoncheck compare_self_ratio_1_same "$T/self/compare.json" && ok || bad "self: ratio 1 and same"

# ---- too few repetitions: with 3 per side the smallest two-sided p is 2/20 = 0.1 > 0.05 ---------
python3 - "$T/a/throughput.json" "$T/slow/throughput.json" "$T/few_a" "$T/few_slow" <<'PY' || bad "making 3-rep runs"
import json, os, sys
for src, dst in ((sys.argv[1], sys.argv[3]), (sys.argv[2], sys.argv[4])):
    d = json.load(open(src))
    for r in d["results"]:
        for k in ("evals_per_s_reps", "normalised_reps", "normalised_cpu_reps"):
            r[k] = r.get(k, [])[:3]
    d.pop("rows", None)   # as the previous version wrote it: read by the layout edited here
    d["schema"] = "brdfbench.throughput/3"
    os.makedirs(dst)
    json.dump(d, open(os.path.join(dst, "throughput.json"), "w"))
PY
"$BIN" compare "$T/few_a" "$T/few_slow" --out "$T/few" --quiet --fail-if-slower 0 2>"$T/err" && ok ||
    bad "undecided rows must not fail --fail-if-slower: $(cat "$T/err")"
jsoncheck compare_3_repetitions_undecided "$T/few/compare.json" && ok || bad "3 repetitions: undecided"

# ---- two real runs: matched, the Hodges-Lehmann ratio of the normalised rates per CPU second
# (recomputed here: the median of the 25 ratios b_j / a_i); the share of "same" is reported ----
"$BIN" compare "$T/a" "$T/a2" --out "$T/real" --quiet 2>"$T/err" && ok || bad "a against a2: $(cat "$T/err")"
jsoncheck compare_two_real_runs "$T/real/compare.json" "$T/a/throughput.json" "$T/a2/throughput.json" && ok || bad "two real runs"

# ---- rows in only some runs ----------------------------------------------------------------
python3 - "$T/a/throughput.json" "$T/mixed" <<'PY' || bad "making the mismatched run"
import json, os, sys
d = json.load(open(sys.argv[1]))
d["results"] = [r for r in d["results"] if r["label"] != "phong"]   # phong only in a
extra = json.loads(json.dumps(d["results"][-1]))
extra["label"] = extra["model"] = "lyon:k=3"                       # lyon only in mixed
d["results"].append(extra)
# the file edited in its layout, as the previous version wrote it (no "rows" member): read by
# that layout, so the edit is what compare sees
d.pop("rows", None)
d["schema"] = "brdfbench.throughput/3"
os.makedirs(sys.argv[2])
json.dump(d, open(os.path.join(sys.argv[2], "throughput.json"), "w"))
PY
"$BIN" compare "$T/a" "$T/mixed" --out "$T/mix" >"$T/table" 2>"$T/err" && ok || bad "mismatched: $(cat "$T/err")"
jsoncheck compare_mismatched_rows_listed "$T/mix/compare.json" && ok || bad "mismatched rows listed"
grep -q "rows found in only some of the runs" "$T/table" && grep -q "phong | default | n uniform .*(not in this run)" "$T/table" &&
    ok || bad "table does not list the unmatched rows"

# ---- accuracy: 4th significant digit, signed change, --fail-if-less-accurate -------------------
python3 - "$T/acc/accuracy.json" "$T/acc2" <<'PY' || bad "making the changed accuracy run"
import json, os, sys
d = json.load(open(sys.argv[1]))
for r in d["results"]:
    if r["label"] == "cq2":
        r["epicentre"]["max_rel"] *= 1.01          # moves the 3rd digit: changed, worse
        r["attenuation"]["max_abs"] *= 0.99        # changed, better
    if r["label"] == "fq2":
        r["epicentre"]["max_rel"] *= 1 + 1e-9      # far below the 4th digit: unchanged
# edited in its layout, as the previous version wrote it (no "rows" member): read by that layout
d.pop("rows", None)
d["schema"] = "brdfbench.accuracy/1"
os.makedirs(sys.argv[2])
json.dump(d, open(os.path.join(sys.argv[2], "accuracy.json"), "w"))
PY
expect 1 "cq2 .*epicentre.max_rel" compare "$T/acc" "$T/acc2" --out "$T/c5" --fail-if-less-accurate
jsoncheck compare_accuracy_verdicts "$T/c5/compare.json" "$T/acc/accuracy.json" "$T/acc2/accuracy.json" && ok || bad "accuracy verdicts"
"$BIN" compare "$T/acc" "$T/acc2" --out "$T/c6" --quiet 2>"$T/err" && ok || bad "without the flag a change exits 0"
# the better direction does not fail
"$BIN" compare "$T/acc2" "$T/acc" --out "$T/c7" --quiet --fail-if-less-accurate 2>"$T/err"
[ $? -eq 1 ] && grep -q "attenuation.max_abs" "$T/err" && ! grep -q "epicentre.max_rel" "$T/err" && ok ||
    bad "reversed accuracy: only attenuation is worse: $(cat "$T/err")"

# ---- render and frontier files (synthetic, keys as their writers use them) ------------------
python3 - "$T" <<'PY' || bad "making render and frontier files"
import json, os, sys
t = sys.argv[1]
def render(ms, psnr):
    return {"schema": "brdfbench.render/1", "context": {"device": "dev"}, "scenes": [{
        "scene": "spheres", "image": {"width": 96, "height": 54},
        "models": [{"model": "cq2", "metrics": {"max_abs": 0.25, "rmse": 0.01, "psnr_db": psnr}},
                   {"model": "phong", "metrics": {"max_abs": 0, "rmse": 0, "psnr_db": None}}],
        "timings": [{"width": 96, "height": 54, "entries": [
            {"name": "cq2", "model": "cq2", "median_ms": ms, "min_ms": ms * 0.9, "max_ms": ms * 1.1,
             "mpixel_per_s": 5.184 / ms}]}]}]}
for name, ms, psnr in (("r1", 1.0, 40.0), ("r2", 2.0, 39.0), ("r3", 1.05, 40.0)):
    os.makedirs(os.path.join(t, name))
    json.dump(render(ms, psnr), open(os.path.join(t, name, "render.json"), "w"))
def frontier(scale, rel):
    # the layout frontier writes (brdfbench.frontier/1: no rows member, read by its layout)
    def model(name, kind, rate, max_rel, max_abs, psnr):
        r = {"min": 0.9 * rate, "median": rate, "max": 1.1 * rate}
        return {"model": name, "kind": kind, "source": "", "on_front": True, "status": "ok",
                "rate_uniform": r, "rate_varying": r, "n_2_1000": {"max_rel": max_rel, "max_abs": max_abs},
                "n_16_1000": {"max_rel": max_rel, "max_abs": max_abs}, "psnr_db": psnr}
    return {"schema": "brdfbench.frontier/1", "context": {"device": "dev", "rounds": 2, "reps": 3}, "models": [
        model("fq2", "paper", 1e10 * scale, rel, 0.1278, 41.5), model("cq2", "paper", 1.1e10, 0.07588, 0.1616, 42.8)]}
json.dump(frontier(1.0, 0.012567), open(os.path.join(t, "f1.json"), "w"))
# with each launch's rate: r5's five launches all take twice as long as r4's, r6's are r4's
def with_reps(scale):
    d = render(1.0 * scale, 40.0)
    ms = [x * scale for x in (0.9, 0.95, 1.0, 1.05, 1.1)]
    d["scenes"][0]["timings"][0]["entries"][0]["mpixel_per_s_reps"] = [5.184 / m for m in reversed(ms)]
    return d
for name, scale in (("r4", 1.0), ("r5", 2.0), ("r6", 1.0)):
    os.makedirs(os.path.join(t, name))
    json.dump(with_reps(scale), open(os.path.join(t, name, "render.json"), "w"))
json.dump(frontier(0.5, 0.012600), open(os.path.join(t, "f2.json"), "w"))
PY
"$BIN" compare "$T/r1" "$T/r2" "$T/r3" --out "$T/c8" --quiet 2>"$T/err" && ok || bad "render: $(cat "$T/err")"
jsoncheck compare_render_verdicts "$T/c8/compare.json" && ok || bad "render verdicts"
"$BIN" compare "$T/r4" "$T/r5" "$T/r6" --out "$T/c10" --quiet 2>"$T/err" && ok || bad "render with reps: $(cat "$T/err")"
jsoncheck compare_render_verdicts_from_launches_rates "$T/c10/compare.json" && ok || bad "render verdicts from the launches' rates"
# a rates array that is not numbers: exit 2 naming the file
python3 - "$T" <<'PY'
import json, os, sys
t = sys.argv[1]
d = json.load(open(os.path.join(t, "r4", "render.json")))
d["scenes"][0]["timings"][0]["entries"][0]["mpixel_per_s_reps"] = ["fast"]
os.makedirs(os.path.join(t, "r7"))
json.dump(d, open(os.path.join(t, "r7", "render.json"), "w"))
PY
expect 2 "r7/render.json:[0-9]+:[0-9]+: " compare "$T/r4" "$T/r7" --out "$T/c11" --quiet
# frontier's rates are what its page shows, of direction neither (2 rounds of a few launches: no
# speed verdict; throughput.json's rates are the timed ones): half the rate does not fail
# --fail-if-slower, a larger max delta fails --fail-if-less-accurate
"$BIN" compare "$T/f1.json" "$T/f2.json" --out "$T/c12" --quiet --fail-if-slower 10 2>"$T/err" && ok \
    || bad "frontier: a rate of direction neither failed --fail-if-slower: $(cat "$T/err")"
"$BIN" compare "$T/f1.json" "$T/f2.json" --out "$T/c9" --quiet --fail-if-less-accurate 2>"$T/err"
[ $? -eq 1 ] && grep -q "fq2 n_2_1000.max_rel" "$T/err" && ok || bad "frontier: fq2's larger max delta must fail: $(cat "$T/err")"
jsoncheck compare_frontier_rows "$T/c9/compare.json" && ok || bad "frontier rows"

# ---- the kernel sources' fingerprints: a kernel changed without a commit shows in the context
SRC=${SRC_DIR:?SRC_DIR must name the source tree}
cp -r "$SRC/kernels" "$T/k_same" && cp -r "$SRC/kernels" "$T/k_edit" && echo "/* edited */" >>"$T/k_edit/brdf_models.h"
"$BIN" "${TP[@]}" --models cq2 --kernel-dir "$T/k_same" --out "$T/ks" 2>"$T/err" && ok || bad "kernel-dir run: $(cat "$T/err")"
"$BIN" "${TP[@]}" --models cq2 --kernel-dir "$T/k_edit" --out "$T/ke" 2>"$T/err" && ok || bad "kernel-dir run: $(cat "$T/err")"
"$BIN" compare "$T/a" "$T/ks" "$T/ke" --out "$T/ck" --quiet 2>"$T/err" && ok || bad "compare kernel runs: $(cat "$T/err")"
jsoncheck compare_kernel_fingerprints_in_context "$T/ck/compare.json" && ok || bad "kernel fingerprints in the context"

# ---- fit.json: the fitted coefficients and figures, the other models by name ------------------
"$BIN" fit --n-min 2 --n-max 30 --out "$T/fit" --quiet >/dev/null 2>"$T/err" && ok || bad "fit run: $(cat "$T/err")"
python3 - "$T/fit/fit.json" "$T/fit2" <<'PY' || bad "making the changed fit"
import json, os, sys
d = json.load(open(sys.argv[1]))
d["a"] *= 1.001          # a coefficient moved in its 4th digit: changed (no better or worse)
d["max_rel"] *= 0.99     # the fit's max delta 1% lower: changed, better
# the file edited in its layout, as the previous version wrote it (no "rows" member): read by
# that layout, so the edit is what compare sees
d.pop("rows", None)
d["schema"] = "brdfbench.fit/1"
os.makedirs(sys.argv[2])
json.dump(d, open(os.path.join(sys.argv[2], "fit.json"), "w"))
PY
"$BIN" compare "$T/fit" "$T/fit2" --out "$T/cfit" --quiet --fail-if-less-accurate 2>"$T/err" && ok ||
    bad "fit: a better figure must not fail: $(cat "$T/err")"
jsoncheck compare_fit_rows "$T/cfit/compare.json" "$T/fit/fit.json" && ok || bad "fit rows"

# ---- several devices in one run: the same PoCL device twice --------------------------------
"$BIN" "${TP[@]}" --device 0,0 --out "$T/dev" 2>"$T/err" && ok || bad "--device 0,0: $(cat "$T/err")"
jsoncheck compare_device_0_0_rows_tagged "$T/dev/throughput.json" && ok || bad "--device 0,0: rows tagged"
for k in 1 2; do [ -s "$T/dev/devices/$k/throughput.json" ] && [ -s "$T/dev/devices/$k/throughput.csv" ] && ok ||
    bad "devices/$k lacks its own outputs"; done
"$BIN" compare "$T/dev" --out "$T/devc" >"$T/table" 2>"$T/err" && ok || bad "compare one run of 2 devices: $(cat "$T/err")"
jsoncheck compare_devices_side_by_side "$T/devc/compare.json" "$T/dev/throughput.json" && ok || bad "devices side by side"
# two runs of two devices each match row by row, device by device
"$BIN" compare "$T/dev" "$T/dev" --out "$T/devc2" --quiet 2>"$T/err" && ok || bad "dev against dev: $(cat "$T/err")"
jsoncheck compare_dev_against_dev_rows_keyed "$T/devc2/compare.json" && ok || bad "dev against dev: rows keyed by device"
"$BIN" accuracy --models cq2 --n-max 20 --samples 64 --device 0,0 --out "$T/accdev" --quiet 2>"$T/err" && ok ||
    bad "accuracy --device 0,0: $(cat "$T/err")"
jsoncheck compare_accuracy_rows_tagged "$T/accdev/accuracy.json" && ok || bad "accuracy rows tagged"
expect 2 "--device: device 7 is out of range for platform 0 \(accepted: 0 to" "${TP[@]}" --device 0:7 --out "$T/x8"
expect 2 "--device: 'x' is not N or P:D" "${TP[@]}" --device 0,x --out "$T/x9"
expect 2 "all and lists are taken by throughput, accuracy and render" fit --device all
expect 2 "--min-time" "${TP[@]}" --device 0,0 --min-time 99 --out "$T/x10"
for i in 8 9 10; do [ ! -e "$T/x$i" ] && ok || bad "exit 2 left $T/x$i behind"; done

# ---- exit 2: one line, nothing written ----------------------------------------------------
expect 2 "nothere: No such file" compare "$T/nothere" "$T/a" --out "$T/x1"
mkdir -p "$T/empty"
expect 2 "empty: no result file" compare "$T/a" "$T/empty" --out "$T/x2"
python3 - "$T/a/throughput.json" "$T/old" <<'PY'
import json, os, sys
d = json.load(open(sys.argv[1]))
d["schema"] = "brdfbench.throughput/1"
os.makedirs(sys.argv[2])
json.dump(d, open(os.path.join(sys.argv[2], "throughput.json"), "w"))
PY
expect 2 'schema "brdfbench.throughput/1", compare reads "brdfbench.throughput/5"' compare "$T/a" "$T/old" --out "$T/x3"
expect 2 "no row in common" compare "$T/a" "$T/acc" --out "$T/x4"
expect 2 "one run holds one device" compare "$T/a" --out "$T/x5"
expect 2 "expected BASELINE RUN" compare
expect 2 "unknown option '--bogus'" compare "$T/a" "$T/a2" --bogus
expect 2 "--alpha" compare "$T/a" "$T/a2" --alpha 1.5
expect 2 "--fail-if-slower" compare "$T/a" "$T/a2" --fail-if-slower 101
echo '{"schema": "brdfbench.something/1"}' >"$T/other.json"
expect 2 'schema "brdfbench.something/1" is not a result file with figures' compare "$T/a" "$T/other.json" --out "$T/x6"
printf '{"schema": ' >"$T/broken.json"
expect 2 "broken.json:1" compare "$T/a" "$T/broken.json" --out "$T/x7"
for i in 1 2 3 4 5 6 7; do
    [ ! -e "$T/x$i" ] && ok || bad "exit 2 left $T/x$i behind"
done
[ "$(wc -l <"$T/err")" -eq 1 ] && ok || bad "exit 2 message is not one line: $(cat "$T/err")"

# ---- exit 3: an output folder that cannot be made -------------------------------------------
touch "$T/afile"
expect 3 "afile" compare "$T/a" "$T/a2" --out "$T/afile/sub" --quiet

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
