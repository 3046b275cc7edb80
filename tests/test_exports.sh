#!/usr/bin/env bash
# test_exports.sh - `brdfbench rows --format gbench|bmf|action|action-smaller`: a hand-written
# rows document exported and checked field by field against values worked by hand below, each
# format's members checked against the field lists of its published documentation (written
# here, not taken from the program), and google/benchmark's own compare.py (Debian's
# libbenchmark-tools, the real client) run on the gbench exports of two real throughput runs.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init

# Two timed rows and an accuracy row. m1's repetitions 1e8, 2e8, 4e8 per second; m2 failed.
cat >"$T/rows.json" <<'EOF'
{"schema": "brdfbench.rows/1",
 "source": {"schema": "brdfbench.throughput/3", "kind": "throughput", "file": "throughput.json"},
 "context": {"device": "cpu0", "git_revision": "abc123", "date": "2026-01-02T03:04:05Z", "host_cores": "4"},
 "rows": [
  {"device": "", "model": "m1", "keys": {"label": "m1", "variant": "default", "n_mode": "uniform"},
   "row": "m1 | default | n uniform", "status": "ok",
   "metrics": [{"name": "evals_per_s", "unit": "1/s", "direction": "higher", "timed": true, "value": 2e8,
                "min": 1e8, "max": 4e8, "reps": [1e8, 2e8, 4e8]}]},
  {"device": "", "model": "m2", "keys": {"label": "m2", "variant": "default", "n_mode": "uniform"},
   "row": "m2 | default | n uniform", "status": "failed", "reason": "build failed",
   "metrics": [{"name": "evals_per_s", "unit": "1/s", "direction": "higher", "timed": true, "value": null}]},
  {"device": "", "model": "m3", "keys": {"label": "m3"}, "row": "m3", "status": "ok",
   "metrics": [{"name": "max_rel", "unit": "1", "direction": "lower", "timed": false, "value": 0.125},
               {"name": "psnr", "unit": "dB", "direction": "higher", "timed": false, "value": 40.5}]}
 ]}
EOF
for f in gbench bmf action action-smaller; do
    "$BIN" rows "$T/rows.json" --format $f --output "$T/x.$f.json" 2>"$T/err" && ok || bad "--format $f: $(cat "$T/err")"
done

python3 - "$T" <<'EOF' && ok || bad "field checks of the exports"
import json, math, sys
T = sys.argv[1]
fails = []
def check(cond, what):
    if not cond:
        fails.append(what)
def close(a, b, rel=1e-9):
    return isinstance(a, (int, float)) and abs(a - b) <= rel * abs(b)

# google/benchmark JSON (its JSONReporter: context, benchmarks[]; a run's members name,
# family_index, per_family_instance_index, run_name, run_type, repetitions, repetition_index,
# threads, iterations, real_time, cpu_time, time_unit, items_per_second; an aggregate has
# aggregate_name and aggregate_unit instead of repetition_index; an error error_occurred and
# error_message).
g = json.load(open(T + "/x.gbench.json"))
check(set(g) == {"context", "benchmarks"}, "gbench top-level members")
check(g["context"]["date"] == "2026-01-02T03:04:05Z" and g["context"]["num_cpus"] == 4, "gbench context")
runs = [b for b in g["benchmarks"] if b.get("run_type") == "iteration" and not b.get("error_occurred")]
aggs = {b["aggregate_name"]: b for b in g["benchmarks"] if b.get("run_type") == "aggregate"}
errs = [b for b in g["benchmarks"] if b.get("error_occurred")]
run_fields = {"name", "family_index", "per_family_instance_index", "run_name", "run_type", "repetitions",
              "repetition_index", "threads", "iterations", "real_time", "cpu_time", "time_unit", "items_per_second"}
for b in runs:
    check(run_fields <= set(b), "gbench run lacks %s" % (run_fields - set(b)))
    check(b["name"] == "m1/default/n uniform" and b["run_name"] == b["name"], "gbench run name " + b["name"])
    check(b["time_unit"] == "us" and b["repetitions"] == 3 and b["iterations"] == 1, "gbench run members")
# a million items per iteration: 1e6 / 1e8 s = 10 ms = 10000 us, 5000 us, 2500 us (worked by hand)
check([b["repetition_index"] for b in runs] == [0, 1, 2], "gbench repetition_index")
for b, us, rate in zip(runs, [10000, 5000, 2500], [1e8, 2e8, 4e8]):
    check(close(b["real_time"], us) and close(b["cpu_time"], us) and close(b["items_per_second"], rate),
          "gbench rep %s" % b)
check(set(aggs) == {"mean", "median", "stddev", "cv"}, "gbench aggregates %s" % list(aggs))
for name, b in aggs.items():
    check(b["name"] == "m1/default/n uniform_" + name and b["run_name"] == "m1/default/n uniform", "agg name")
    check({"aggregate_name", "aggregate_unit", "real_time", "cpu_time", "time_unit", "repetitions"} <= set(b), "agg fields")
# by hand: times 10000, 5000, 2500 us: mean 5833.33; median 5000; deviations 4166.67, -833.33,
# -3333.33, squares summing to 29166666.7, over n - 1 = 2: 14583333.3, sqrt 3818.81; cv
# 3818.81 / 5833.33 = 0.654654. Rates: mean 2.33333e8, median 2e8, stddev 1.52753e8.
check(close(aggs["mean"]["real_time"], 5833.3333, 1e-6), "mean time")
check(close(aggs["median"]["real_time"], 5000), "median time")
check(close(aggs["stddev"]["real_time"], 3818.813, 1e-6), "stddev time")
check(close(aggs["cv"]["real_time"], 0.654654, 1e-5) and aggs["cv"]["aggregate_unit"] == "percentage", "cv")
check(close(aggs["mean"]["items_per_second"], 2.3333333e8, 1e-6), "mean rate")
check(close(aggs["stddev"]["items_per_second"], 1.52753e8, 1e-5), "stddev rate")
check(len(errs) == 1 and errs[0]["name"] == "m2/default/n uniform" and errs[0]["error_message"] == "build failed"
      and "real_time" not in errs[0], "gbench error entry")
check(not any(b["name"].startswith("m3") for b in g["benchmarks"]), "gbench holds an accuracy figure")

# Bencher Metric Format: { benchmark: { measure: { value, lower_value?, upper_value? } } },
# numbers only.
m = json.load(open(T + "/x.bmf.json"))
check(set(m) == {"m1 | default | n uniform", "m3"}, "bmf benchmarks %s" % list(m))
check(m["m1 | default | n uniform"] == {"evals_per_s": {"value": 2e8, "lower_value": 1e8, "upper_value": 4e8}}, "bmf m1")
check(m["m3"] == {"max_rel": {"value": 0.125}, "psnr": {"value": 40.5}}, "bmf m3")
for bench in m.values():
    for meas in bench.values():
        check(set(meas) <= {"value", "lower_value", "upper_value"} and "value" in meas, "bmf measure fields")
        check(all(isinstance(v, (int, float)) for v in meas.values()), "bmf numbers")

# github-action-benchmark custom JSON: an array of { name, unit, value, range?, extra? };
# one direction per file (customBiggerIsBetter / customSmallerIsBetter).
for f, want in (("action", {"m1 | default | n uniform": ("1/s", 2e8), "m3 | psnr": ("dB", 40.5)}),
                ("action-smaller", {"m3 | max_rel": ("1", 0.125)})):
    a = json.load(open(T + "/x.%s.json" % f))
    check(isinstance(a, list), f + " is an array")
    check({e["name"]: (e["unit"], e["value"]) for e in a} == want, f + " entries %s" % a)
    for e in a:
        check({"name", "unit", "value"} <= set(e) <= {"name", "unit", "value", "range", "extra"}, f + " fields")
        check(isinstance(e["name"], str) and isinstance(e["unit"], str) and isinstance(e["value"], (int, float)), f + " types")
        check(isinstance(e.get("range", ""), str) and isinstance(e.get("extra", ""), str), f + " range/extra are text")
        check("commit: abc123" in e["extra"], f + " extra names the commit")
# (4e8 - 1e8) / 2 = 1.5e8 either side
check(json.load(open(T + "/x.action.json"))[0].get("range") == "± 1.5e+08", "action range")
if fails:
    print("\n".join(fails), file=sys.stderr)
    sys.exit(1)
EOF

# Nothing of a direction or no timed figure: exit 2, nothing written.
cat >"$T/acc.json" <<'EOF'
{"schema": "brdfbench.rows/1", "source": {"schema": "brdfbench.accuracy/1", "kind": "accuracy", "file": "accuracy.json"},
 "context": {}, "rows": [{"device": "", "model": "m3", "keys": {"label": "m3"}, "row": "m3", "status": "ok",
  "metrics": [{"name": "max_rel", "unit": "1", "direction": "lower", "timed": false, "value": 0.125}]}]}
EOF
expect 2 "no timed figure" rows "$T/acc.json" --format gbench --output "$T/none.json"
[ ! -e "$T/none.json" ] && ok || bad "gbench with nothing timed wrote a file"
expect 2 "no figure where higher is better \(try --format action-smaller\)" rows "$T/acc.json" --format action
expect 2 "accepted: md, csv, json\) nor an export \(gbench, bmf, action, action-smaller\)" rows "$T/acc.json" --format junit

# compare.py, the real client, on two real throughput runs (tiny: one model, ten repetitions).
PY=/usr/bin/python3   # Debian's interpreter: compare.py needs its python3-scipy
COMPARE=/usr/share/benchmark/compare.py
for r in a b; do
    "$BIN" throughput --models cq2 --reps 10 --min-time 0.002 --work-items 8 --variants default --no-host-c \
        --no-sweep --quiet --out "$T/run_$r" 2>"$T/err"
    rc=$?
    if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "$pass passed, $fail failed, 1 skipped"; exit 77; fi
    [ $rc -eq 0 ] && ok || bad "throughput run $r: $(cat "$T/err")"
    "$BIN" rows "$T/run_$r" --format gbench --output "$T/$r.json" 2>"$T/err" && ok || bad "export $r: $(cat "$T/err")"
done
if [ ! -f "$COMPARE" ]; then
    bad "$COMPARE missing (libbenchmark-tools, scripts/setup.sh)"
else
    "$PY" "$COMPARE" --no-color benchmarks "$T/a.json" "$T/b.json" >"$T/cmp" 2>"$T/err"
    rc=$?
    [ $rc -eq 0 ] && ok || bad "compare.py exit $rc: $(tail -3 "$T/err")"
    for row in "cq2/default/n uniform" "cq2/default/n varying" "peak (reference kernel)"; do
        # a repetition line with the time change, then the U test of the repetitions (ten for a
        # model; the reference kernel is timed in every round, more often)
        n=10; case $row in peak*) n='[0-9]+' ;; esac
        grep -qE "^$(printf '%s' "$row" | sed 's/[()]/\\&/g') +[-+][0-9]+\.[0-9]+ " "$T/cmp" && ok || bad "compare.py lacks $row"
        grep -qE "^$(printf '%s' "$row" | sed 's/[()]/\\&/g')_pvalue +[0-9.]+ .*U Test, Repetitions: $n vs $n" "$T/cmp" \
            && ok || bad "compare.py: no U test for $row: $(head -5 "$T/cmp")"
    done
    grep -q "^OVERALL_GEOMEAN" "$T/cmp" && ok || bad "compare.py: no geomean line"
fi

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
