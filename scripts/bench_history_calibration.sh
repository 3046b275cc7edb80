#!/usr/bin/env bash
# bench_history_calibration.sh - how often `brdfbench history` calls a change where there is
# none, and whether it finds a planted one at the right run: series of real throughput runs of
# identical code, with and without a competing CPU load, and the same series with a 30% step
# planted in one model from run 7 on.
#
#   bash scripts/bench_history_calibration.sh [SERIES] [RUNS]     (default 3 series of 12 runs)
#
# Conditions, SERIES series of RUNS throughput runs each (the same binary and flags):
#   flat        the runs one after the other, nothing changed;
#   flat-load   the same with a CPU-bound process (a shell loop) running during the second half
#               of the runs (the load changes, the code does not: the normalised rates should
#               not move);
#   planted     each flat series again, copies of its files with one model's (STEP_MODEL)
#               rates, normalised rates and their ranges times 0.7 from run STEP_FROM on:
#               a 30% slowdown of that model, synthetic from real runs.
#   synthetic   no device, no timing: RUNS rows documents of 200 independent rows each, every
#               repetition exp(run offset + noise), the run offset N(0, RUN_SD) per row and
#               run (the drift between runs that the normalisation leaves), the noise
#               N(0, REP_SD); 20 of the rows with the 30% step from STEP_FROM. Seeded: the same
#               figures every time. It shows the rule's error rates under a stated noise model.
# Printed per condition: the rows, the share of rows with no change called (the calibration
# goal: at least 95% on flat and flat-load), and for planted and synthetic the share of the
# planted rows (STEP_MODEL's; synthetic's s00..s19) whose one change is called at STEP_FROM,
# the share of them with a change at STEP_FROM among others, and the share of the other rows
# with any change (for synthetic the calibration figure).
#
# Also printed: the machine's load while the runs were made (the 1-minute load average each
# run's context records at its start: min, median, max), and on stderr every change called,
# as "condition-series row: run index (ratio)", so that a share can be traced to its runs.
#
# Environment: BRDFBENCH (default build/brdfbench), MODELS (default cq2,fq2,phong), TP_FLAGS
# (default below), STEP_MODEL (default fq2), STEP_FROM (default 7), CONDITIONS (default
# "synthetic flat flat-load"; planted always follows flat), RUN_SD and REP_SD (synthetic's noise,
# default 0.02 and 0.03), MIN_CHANGES (history's --min-change, percent; default 10; a list such
# as "10 25" evaluates the same runs once per value, a line each), KEEP=1 keeps the runs.
# A benchmark, not a test: its figures go into notes, never into assertions.
set -euo pipefail
cd "$(dirname "$0")/.."
B=${BRDFBENCH:-build/brdfbench}
SERIES=${1:-3}
RUNS=${2:-12}
MODELS=${MODELS:-cq2,fq2,phong}
TP_FLAGS=${TP_FLAGS:---reps 10 --min-time 0.005 --work-items 8 --variants default --no-host-c --no-sweep --quiet}
STEP_MODEL=${STEP_MODEL:-fq2}
STEP_FROM=${STEP_FROM:-7}
CONDS=${CONDITIONS:-synthetic flat flat-load}
RUN_SD=${RUN_SD:-0.02}
REP_SD=${REP_SD:-0.03}
MIN_CHANGES=${MIN_CHANGES:-10}
W=$(mktemp -d)
[ -n "${KEEP:-}" ] && echo "runs kept in $W" || trap 'rm -rf "$W"' EXIT

hog_pid=
hog_start() { (while :; do :; done) & hog_pid=$!; }
hog_stop() { if [ -n "$hog_pid" ]; then kill "$hog_pid" 2>/dev/null || true; wait "$hog_pid" 2>/dev/null || true; fi; hog_pid=; }
trap 'hog_stop' INT TERM

series() {   # DIR load|none: RUNS runs into DIR/runNN
    local dir=$1 load=$2
    mkdir -p "$dir"
    for i in $(seq -w 1 "$RUNS"); do
        if [ "$load" = load ] && [ "$((10#$i))" -gt "$((RUNS / 2))" ]; then hog_start; fi
        "$B" throughput $TP_FLAGS --models "$MODELS" --out "$dir/run$i" >/dev/null
        hog_stop
    done
}

plant() {   # FROM TO: copies of FROM's runs with STEP_MODEL 0.7x from STEP_FROM on
    python3 - "$1" "$2" "$STEP_MODEL" "$STEP_FROM" <<'PY'
import json, os, shutil, sys
src, dst, model, start = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
def scale(v, f):
    if isinstance(v, (int, float)) and not isinstance(v, bool):
        return v * f
    if isinstance(v, list):
        return [scale(x, f) for x in v]
    if isinstance(v, dict):
        return {k: scale(x, f) for k, x in v.items()}
    return v
for run in sorted(os.listdir(src)):
    shutil.copytree(os.path.join(src, run), os.path.join(dst, run))
    if int(run[3:]) < start:
        continue
    path = os.path.join(dst, run, "throughput.json")
    d = json.load(open(path))
    for r in d["results"]:
        if r.get("label") == model:
            # every rate of the row and its normalised forms, with their ranges
            for k in list(r):
                if k.startswith("evals_per_s") or k.startswith("normalised"):
                    r[k] = scale(r[k], 0.7)
    json.dump(d, open(path, "w"), indent=1)
PY
}

synthetic() {   # DIR SEED: RUNS rows documents, 200 rows each; rows s00..s19 with the step
    python3 - "$1" "$2" "$RUNS" "$STEP_FROM" "$RUN_SD" "$REP_SD" <<'PY'
import json, math, os, random, sys
out, seed, runs, start, run_sd, rep_sd = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), \
    float(sys.argv[5]), float(sys.argv[6])
rnd = random.Random(seed)
os.makedirs(out, exist_ok=True)
offset = [[rnd.gauss(0, run_sd) for _ in range(runs)] for _ in range(200)]
for r in range(runs):
    rows = []
    for i in range(200):
        name = "%s%02d" % ("s" if i < 20 else "n", i)
        step = math.log(0.7) if i < 20 and r + 1 >= start else 0.0
        reps = [1e8 * math.exp(offset[i][r] + step + rnd.gauss(0, rep_sd)) for _ in range(10)]
        srt = sorted(reps)
        rows.append({"device": "", "model": name, "keys": {"label": name}, "row": name, "status": "ok",
                     "metrics": [{"name": "evals_per_s", "unit": "1/s", "direction": "higher", "timed": True,
                                  "value": (srt[4] + srt[5]) / 2, "min": srt[0], "max": srt[-1], "reps": reps,
                                  "normalised_reps": [v / 1e11 for v in reps]}]})
    json.dump({"schema": "brdfbench.rows/1",
               "source": {"schema": "brdfbench.throughput/3", "kind": "throughput", "file": "throughput.json"},
               "context": {"device": "synthetic", "date": "2026-01-01T00:00:%02dZ" % r}, "rows": rows},
              open("%s/run%02d.json" % (out, r + 1), "w"))
PY
}

# counts of one history: "ROWS NOCHANGE STEP_ROWS STEP_AT_RIGHT_RUN OTHER_ROWS OTHER_CHANGED
# STEP_FOUND" (STEP_AT_RIGHT_RUN: planted rows whose one change is at STEP_FROM; STEP_FOUND:
# planted rows with a change at STEP_FROM, whatever else is called in them);
# every change called goes to stderr, tagged with TAG
tally() {
    python3 - "$1/history.json" "$STEP_MODEL" "$STEP_FROM" "${2:-}" <<'PY'
import json, sys
h = json.load(open(sys.argv[1]))
model, start, tag = sys.argv[2], int(sys.argv[3]), sys.argv[4]
rows = [r for r in h["rows"] if not r["label"].startswith("peak")]
step = [r for r in rows if r["label"].split(" | ")[0] == model or (model == "s" and r["label"].startswith("s"))]
other = [r for r in rows if r not in step]
right = sum(1 for r in step if len(r["changes"]) == 1 and r["changes"][0]["index"] == start)
if tag != "synthetic":
    for r in rows:
        for c in r["changes"]:
            print("  %s %s: run %d (%.3f)" % (tag, r["label"], c["index"], c["ratio"]), file=sys.stderr)
found = sum(1 for r in step if any(c["index"] == start for c in r["changes"]))
print(len(rows), sum(1 for r in rows if not r["changes"]), len(step), right, len(other),
      sum(1 for r in other if r["changes"]), found)
PY
}

# the 1-minute load averages at the start of the runs in DIR, one a line
loads() {
    python3 - "$1" <<'PY'
import json, os, sys
for run in sorted(os.listdir(sys.argv[1])):
    ctx = json.load(open(os.path.join(sys.argv[1], run, "throughput.json")))["context"]
    print(ctx.get("throughput", {}).get("loadavg_start", "nan").split()[0])
PY
}

declare -A rows nochange steprows stepright otherrows otherchanged stepfound loadavg
add() {   # COND COUNTS...   (COND: condition@min-change)
    local c=$1
    rows[$c]=$(( ${rows[$c]:-0} + $2 )); nochange[$c]=$(( ${nochange[$c]:-0} + $3 ))
    steprows[$c]=$(( ${steprows[$c]:-0} + $4 )); stepright[$c]=$(( ${stepright[$c]:-0} + $5 ))
    otherrows[$c]=$(( ${otherrows[$c]:-0} + $6 )); otherchanged[$c]=$(( ${otherchanged[$c]:-0} + $7 ))
    stepfound[$c]=$(( ${stepfound[$c]:-0} + $8 ))
}

# history of the runs DIR/run* at every minimum change: "history DIR COND SERIES"
history_all() {
    local mc
    for mc in $MIN_CHANGES; do
        "$B" history "$1"/run* --min-change "$mc" --out "$1-h$mc" >/dev/null
        if [ "$2" = synthetic ]; then
            add "synthetic@$mc" $(STEP_MODEL=s tally "$1-h$mc" synthetic)
        else
            add "$2@$mc" $(tally "$1-h$mc" "$2-$3 min $mc%")
        fi
    done
}

for s in $(seq 1 "$SERIES"); do
    for cond in $CONDS; do
        if [ "$cond" = synthetic ]; then
            synthetic "$W/synthetic-$s" "$s"
            history_all "$W/synthetic-$s" synthetic "$s"
            continue
        fi
        load=none; [ "$cond" = flat-load ] && load=load
        series "$W/$cond-$s" "$load"
        loadavg[$cond]="${loadavg[$cond]:-} $(loads "$W/$cond-$s" | tr '\n' ' ')"
        history_all "$W/$cond-$s" "$cond" "$s"
        if [ "$cond" = flat ]; then
            plant "$W/flat-$s" "$W/planted-$s"
            history_all "$W/planted-$s" planted "$s"
        fi
    done
    echo "series $s of $SERIES done" >&2
done

echo "history calibration: $SERIES series of $RUNS runs, models $MODELS, $TP_FLAGS"
for c in flat flat-load; do
    [ -n "${loadavg[$c]:-}" ] || continue
    python3 -c "import statistics as s, sys; v = [float(x) for x in sys.argv[2:]]; print('%s: 1-minute load average at the runs\' start: min %.2f, median %.2f, max %.2f (%d runs, %s cores)' % (sys.argv[1], min(v), s.median(v), max(v), len(v), '$(nproc)'))" "$c" ${loadavg[$c]}
done
printf '%-10s %6s %6s %22s %30s %26s %24s\n' condition "min %" rows "no change called" "planted rows: one change at $STEP_FROM" \
    "planted rows: a change at $STEP_FROM" "other rows: a change"
share() { [ "$2" -gt 0 ] && python3 -c "print('%d/%d = %.1f%%' % ($1, $2, 100.0 * $1 / $2))" || echo "-"; }
for mc in $MIN_CHANGES; do
    for cond in synthetic flat flat-load planted; do
        c="$cond@$mc"
        [ -n "${rows[$c]:-}" ] || continue
        if [ "$cond" = planted ] || [ "$cond" = synthetic ]; then
            printf '%-10s %6s %6d %22s %30s %26s %24s\n' "$cond" "$mc" "${rows[$c]}" "$(share "${nochange[$c]}" "${rows[$c]}")" \
                "$(share "${stepright[$c]}" "${steprows[$c]}")" "$(share "${stepfound[$c]}" "${steprows[$c]}")" \
                "$(share "${otherchanged[$c]}" "${otherrows[$c]}")"
        else
            printf '%-10s %6s %6d %22s %30s %26s %24s\n' "$cond" "$mc" "${rows[$c]}" "$(share "${nochange[$c]}" "${rows[$c]}")" "-" "-" "-"
        fi
    done
done
