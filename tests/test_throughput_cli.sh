#!/usr/bin/env bash
# test_throughput_cli.sh - `brdfbench throughput` end to end on a tiny configuration: the JSON
# contract (strict, no NaN), the CSV, the printed table, and each bad flag (exit 2, a message
# naming the flag and its accepted range, nothing written). No time is asserted.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init

"$BIN" throughput --models phong,cq2,fq:Q=0.7 --reps 2 --min-time 0.002 --work-items 4 --variants default,denorms-are-zero \
    --sweep-samples 32 --sweep-n-step 100 --sweep-reps 1 --out "$T/run" >"$T/table" 2>"$T/err"
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "tiny run exit $rc: $(cat "$T/err")"
check_json "$T/run/throughput.json" "throughput.json contract" <<'PY'
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
PY
head -1 "$T/run/throughput.csv" | grep -q '^model,label,variant,build_options,n_mode,status,evals_per_s_min' && ok || bad "csv header"
[ "$(wc -l <"$T/run/throughput.csv")" -eq 13 ] && ok || bad "csv rows: $(wc -l <"$T/run/throughput.csv")"
grep -qE '^cq2 +uniform' "$T/table" && grep -q 'accuracy sweep' "$T/table" && ok || bad "table: $(head -c 400 "$T/table")"

# A variant whose program does not build: its rows say so (status and reason), the others are
# measured, the run succeeds. The kernels come from a copy where fast-relaxed-math fails to compile.
SRC=${SRC_DIR:?}
mkdir -p "$T/kern"
cp "$SRC"/kernels/*.cl "$SRC"/kernels/*.h "$T/kern/"
printf '#ifdef __FAST_RELAXED_MATH__\n#error this copy does not build with -cl-fast-relaxed-math\n#endif\n' >>"$T/kern/throughput.cl"
"$BIN" throughput --kernel-dir "$T/kern" --models fvol --reps 1 --min-time 0.002 --work-items 2 --no-sweep \
    --variants default,fast-relaxed-math --out "$T/broken" >"$T/table2" 2>"$T/err2"
rc=$?
[ $rc -eq 0 ] && ok || bad "run with a failing variant exit $rc: $(head -c 300 "$T/err2")"
grep -q 'does not build with -cl-fast-relaxed-math' "$T/err2" && ok || bad "build log shown on stderr"
python3 - "$T/broken/throughput.json" <<'PY' && ok || bad "failed variant rows"
import json, sys
d = json.load(open(sys.argv[1]))
b = {x["variant"]: x for x in d["builds"]}
assert b["default"]["status"] == "ok" and b["fast-relaxed-math"]["status"] == "failed", b
for r in d["results"]:
    if r["variant"] == "fast-relaxed-math":
        assert r["status"] == "failed" and "build" in r["reason"] and r["evals_per_s"]["median"] is None, r
    else:
        assert r["status"] == "ok", r
PY

# bad flags: exit 2, the flag and its accepted range named, no output folder made
expect 2 '--reps: .*in \[1, 1000\]' throughput --reps 0 --out "$T/x1"
expect 2 '--min-time: .*in \[0.0001, 10\]' throughput --min-time 1e9 --out "$T/x2"
expect 2 '--min-time' throughput --min-time abc --out "$T/x3"
expect 2 "--variants: unknown 'fast' \(accepted: default, fast-relaxed-math, denorms-are-zero, ab\)" throughput --variants fast --out "$T/x4"
expect 2 '--n-modes: .*accepted: uniform, varying' throughput --n-modes none --out "$T/x5"
expect 2 '--n-range: not a flag of brdfbench throughput: .*--n-min LO --n-max HI' throughput --n-range 5 --out "$T/x6"
expect 2 '--n-min \(9\) must be below --n-max \(3\)' throughput --n-min 9 --n-max 3 --out "$T/x7"
expect 2 '--work-items: .*in \[1, 65536\]' throughput --work-items 0 --out "$T/x8"
expect 2 '--sweep-samples: .*multiple of 16' throughput --sweep-samples 20 --out "$T/x9"
expect 2 'unknown model' throughput --models nosuch --out "$T/x10"
expect 2 "unknown option '--bogus'" throughput --bogus
for k in 1 2 3 4 5 6 7 8 9 10; do [ -e "$T/x$k" ] && bad "bad flag $k made its output folder"; done
"$BIN" throughput --help >"$T/help" 2>&1 && grep -q -- '--min-time' "$T/help" && ok || bad "--help"

# A/B in one process: --ab-options measures the default build options and the default plus
# OPTIONS in the same rounds; ab/a and ab/b hold one side each, as the default variant, so that
# compare matches them row by row; both sides share the rounds' reference (the same peak rates).
"$BIN" throughput --models fq2,cq2 --ab-options "-cl-fast-relaxed-math" --reps 3 --min-time 0.002 --work-items 4 \
    --variants default --no-host-c --no-sweep --quiet --out "$T/ab" 2>"$T/err" && ok || bad "--ab-options run: $(cat "$T/err")"
python3 - "$T/ab" <<'PY' && ok || bad "--ab-options: the two sides"
import json, sys
full, a, b = (json.load(open(sys.argv[1] + f)) for f in ("/throughput.json", "/ab/a/throughput.json", "/ab/b/throughput.json"))
assert {r["variant"] for r in full["results"]} == {"default", "ab"}, {r["variant"] for r in full["results"]}
key = lambda r: (r["label"], r["variant"], r["n_mode"])
assert sorted(map(key, a["results"])) == sorted(map(key, b["results"])) and len(a["results"]) == 3 * 2
assert all(len(r["normalised_cpu_reps"]) == 3 for r in a["results"] + b["results"])
assert b["context"]["ab"]["side"] == "b" and "-cl-fast-relaxed-math" in b["context"]["build_options"]
assert a["context"]["build_options"] == "" and a["peak"]["flops_per_s_reps"] == b["peak"]["flops_per_s_reps"]
ab = {(r["label"], r["n_mode"]): r for r in full["results"] if r["variant"] == "ab"}
for r in b["results"]:
    assert r["evals_per_s_reps"] == ab[(r["label"], r["n_mode"])]["evals_per_s_reps"]
PY
"$BIN" compare "$T/ab/ab/a" "$T/ab/ab/b" --out "$T/abc" --quiet 2>"$T/err" && ok || bad "compare of the A/B sides: $(cat "$T/err")"
expect 2 "--variants: ab is the variant of --ab-options OPTIONS" throughput --variants default,ab --out "$T/x11"
expect 2 "--ab-options: expected OpenCL build options" throughput --ab-options "" --out "$T/x12"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
