#!/usr/bin/env bash
# test_history.sh - `brdfbench history` over rows documents and over the store: 12 runs of
# three models in two n modes, every repetition a known rate times a deterministic jitter
# (within +-3% per repetition, +-2% per run; written below), with changes planted by
# construction: a 30% slowdown of m2 from run 7, and, in a second series, a 30% slowdown of m3
# in the latest run only. Expected: no change on jitter alone; the step called at run 7 in m2's
# two rows and in no other, ratio 0.7 within the jitter, with its interval and p;
# --fail-if-slower exits 1 when the latest run's segment is slower (naming the row), 0 when
# not; a machine 40% slower in the absolute rates alone (normalised ones unmoved) is no change;
# the same runs in another order give the same documents. The runs are given out of order: the
# dates order them. No device.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
PY=/usr/bin/python3

# gen DIR STEP_MODEL STEP_FROM (run index from 1): 12 rows documents DIR/runNN.json
gen() {
    "$PY" - "$@" <<'EOF'
import json, math, os, sys
out, step_model, step_from = sys.argv[1], sys.argv[2], int(sys.argv[3])
# DRIFT=1: the machine 40% slower from run 7 in every row's absolute rates, its normalised
# rates as in the flat series (the reference kernel slowed with it, so the ratio held)
drift = os.environ.get("DRIFT") == "1"
os.makedirs(out, exist_ok=True)
models = {"m1": 1e8, "m2": 2e8, "m3": 5e7}
for r in range(12):
    rows = []
    for mi, (m, rate) in enumerate(models.items()):
        for ni, mode in enumerate(("uniform", "varying")):
            q = 3 * mi + ni   # decorrelates the rows' jitter
            scale = 0.7 if (m == step_model and r + 1 >= step_from) else 1.0
            reps = [rate * scale * (1 + 0.03 * math.sin(1.7 * i + 2.3 * r + q)) * (1 + 0.02 * math.cos(1.3 * r + q))
                    for i in range(10)]
            norm = [v / 1e11 for v in reps]
            if drift and r + 1 >= 7:
                reps = [v * 0.6 for v in reps]
            srt = sorted(reps)
            rows.append({"device": "", "model": m, "keys": {"label": m, "variant": "default", "n_mode": mode},
                         "row": "%s | default | n %s" % (m, mode), "status": "ok",
                         "metrics": [{"name": "evals_per_s", "unit": "1/s", "direction": "higher", "timed": True,
                                      "value": (srt[4] + srt[5]) / 2, "min": srt[0], "max": srt[-1], "reps": reps,
                                      "normalised_reps": norm}]})
    doc = {"schema": "brdfbench.rows/1",
           "source": {"schema": "brdfbench.throughput/3", "kind": "throughput", "file": "throughput.json"},
           "context": {"device": "cpu0", "git_revision": "c%02d" % (r + 1),
                       "date": "2026-03-%02dT10:00:00Z" % (r + 1)},
           "rows": rows}
    json.dump(doc, open("%s/run%02d.json" % (out, r + 1), "w"))
EOF
}
gen "$T/flat" none 99
gen "$T/step" m2 7
gen "$T/last" m3 12
DRIFT=1 gen "$T/drift" none 99
# the files in a shuffled order: the runs' dates put them back
shuffled() { for i in 05 12 01 09 03 07 11 02 08 04 10 06; do echo "$1/run$i.json"; done; }

"$BIN" history $(shuffled "$T/flat") --out "$T/h_flat" --fail-if-slower 10 >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 0 ] && ok || bad "jitter only: exit $rc: $(cat "$T/err")"
grep -q "history: 12 runs (by run date), 6 rows, 0 changes" "$T/out" && ok || bad "jitter only: $(head -3 "$T/out")"
for f in history.json history.md history.png history_normalised.png; do
    [ -s "$T/h_flat/$f" ] && ok || bad "history wrote no $f"
done

"$BIN" history $(shuffled "$T/step") --out "$T/h_step" --fail-if-slower 10 >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 1 ] && ok || bad "step from run 7: exit $rc, expected 1 (the latest run's segment is 0.7x): $(cat "$T/err")"
"$PY" - "$T/h_step/history.json" "$SRC/docs/schemas/brdfbench.history-1.schema.json" <<'EOF' && ok || bad "step from run 7: history.json"
import json, sys
h = json.load(open(sys.argv[1]))
assert h["schema"] == "brdfbench.history/1"
assert [r["name"] for r in h["runs"]] == ["run%02d.json" % (i + 1) for i in range(12)] or \
       [r["name"].rsplit("/", 1)[-1] for r in h["runs"]] == ["run%02d.json" % (i + 1) for i in range(12)], h["runs"]
ch = h["changes"]
# planted: m2's two rows, from run 7 (commit c07), ratio 0.7
assert sorted(c["label"] for c in ch) == ["m2 | default | n uniform", "m2 | default | n varying"], ch
for c in ch:
    assert set(c) >= {"label", "run", "commit", "ratio", "interval", "p"}, c
    assert c["run"].endswith("run07.json") and c["commit"] == "c07" and c["index"] == 7, c
    assert 0.66 < c["ratio"] < 0.74, c
    assert c["interval"][0] <= 0.7 <= c["interval"][1], c
    assert 0 <= c["p"] < 0.05, c
import jsonschema   # python3-jsonschema: the document against docs/schemas (and a broken copy refused)
schema = json.load(open(sys.argv[2]))
jsonschema.validate(h, schema)
broken = json.loads(json.dumps(h))
broken["changes"][0]["p"] = 2
try:
    jsonschema.validate(broken, schema)
    raise AssertionError("a p of 2 passed the schema")
except jsonschema.ValidationError:
    pass
rows = {r["label"]: r for r in h["rows"]}
assert len(rows) == 6 and all(r["basis"] == "normalised" for r in rows.values())
assert all(not r["changes"] for l, r in rows.items() if not l.startswith("m2"))
EOF
grep -c "^cpu0 | m2 | default | n .* evals_per_s: the latest run ([^)]*run12.json) is in a segment 0.[67][0-9]*x the one before, from run 7" "$T/err" | grep -qx 2 \
    && ok || bad "step: --fail-if-slower lines: $(cat "$T/err")"
grep -q "|.*m2 | default | n uniform.* 7 (run07.json)" "$T/h_step/history.md" || grep -q "m2 \\\\| default \\\\| n uniform\|m2 | default" "$T/h_step/history.md" \
    && ok || bad "history.md lacks the change"
# The verdict is reproducible: the same runs, given in another order, give the same documents
# byte for byte (the dates order them; nothing random or timed enters the method).
"$BIN" history $(shuffled "$T/step" | sort -r) --out "$T/h_step_again" >/dev/null 2>"$T/err" &&
    cmp -s "$T/h_step/history.json" "$T/h_step_again/history.json" &&
    cmp -s "$T/h_step/history.md" "$T/h_step_again/history.md" && ok || bad "history of the same runs twice differs"
# History decides on the normalised rates, as compare: the machine 40% slower from run 7 in the
# absolute rates, with the normalised ones those of the flat series, is no change in any row
# (the absolute rates alone would give a change of 0.6 at run 7 in all six).
"$BIN" history $(shuffled "$T/drift") --out "$T/h_drift" >"$T/out" 2>"$T/err" &&
    grep -q "history: 12 runs (by run date), 6 rows, 0 changes" "$T/out" && ok || bad "machine drift: $(head -3 "$T/out" "$T/err")"
# a lenient threshold: a 30% slowdown is not more than 40% slower (the minimum change follows it, as in compare)
"$BIN" history $(shuffled "$T/step") --out "$T/h_step2" --fail-if-slower 40 >"$T/out" 2>"$T/err"
[ $? -eq 0 ] && ok || bad "--fail-if-slower 40 on a 30% step: $(cat "$T/err")"

"$BIN" history $(shuffled "$T/last") --out "$T/h_last" --fail-if-slower 10 >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 1 ] && ok || bad "latest run slower: exit $rc, expected 1"
[ "$(grep -c 'is in a segment' "$T/err")" -eq 2 ] && ! grep 'is in a segment' "$T/err" | grep -qv '^cpu0 | m3 | ' && ok ||
    bad "latest run slower: named rows: $(cat "$T/err")"

# The same through the store: the step is called there too, at run 7.
"$BIN" store add $(shuffled "$T/step") --db "$T/h.sqlite" >/dev/null 2>"$T/err" && ok || bad "store add: $(cat "$T/err")"
"$BIN" history --db "$T/h.sqlite" --out "$T/h_db" >"$T/out" 2>"$T/err" && ok || bad "history --db: $(cat "$T/err")"
grep -q "history: 12 runs (by run date), 6 rows, 2 changes" "$T/out" && ok || bad "history --db: $(head -4 "$T/out")"
[ "$(grep -c 'from run 7 ([^)]*run07.json): 0\.[67]' "$T/out")" -eq 2 ] && ok || bad "history --db: $(cat "$T/out")"

# Commit dates order the history where every run has one: the step series stored with commit
# dates in the reverse order of its run dates (run k committed on day 13 - k) reads backwards,
# so the slow runs 7..12 come first and the change is at the 7th run in commit order, run06,
# a speed-up of 1 / 0.7 = 1.43.
for i in $(seq -w 1 12); do
    day=$(printf '%02d' $((13 - 10#$i)))
    "$BIN" store add "$T/step/run$i.json" --db "$T/c.sqlite" --commit-date "2026-04-${day}T12:00:00+02:00" >/dev/null 2>"$T/err" ||
        bad "store add --commit-date: $(cat "$T/err")"
done
"$BIN" history --db "$T/c.sqlite" --out "$T/h_c" >"$T/out" 2>"$T/err" && ok || bad "history by commit date: $(cat "$T/err")"
"$PY" - "$T/h_c/history.json" <<'EOF' && ok || bad "history by commit date: history.json"
import json, sys
h = json.load(open(sys.argv[1]))
assert h["order"] == "commit date", h["order"]
# +02:00 in UTC: 10:00Z, days 01..12 in order
assert [r["commit_date"] for r in h["runs"]] == ["2026-04-%02dT10:00:00Z" % d for d in range(1, 13)], h["runs"]
assert [r["name"].rsplit("/", 1)[-1] for r in h["runs"]] == ["run%02d.json" % (13 - d) for d in range(1, 13)]
ch = h["changes"]
assert sorted(c["label"] for c in ch) == ["m2 | default | n uniform", "m2 | default | n varying"], ch
for c in ch:
    assert c["index"] == 7 and c["run"].endswith("run06.json") and 1.35 < c["ratio"] < 1.51, c
EOF
expect 2 "--commit-date: 'yesterday' is not a date and time with its zone" store add "$T/step/run01.json" --db "$T/c.sqlite" --commit-date yesterday

# Accuracy figures (not timed): a change where the 4th significant digit moves. Runs 1, 2 give
# max_rel 0.01234 and 0.012341 (the same to 4 digits), run 3 gives 0.01300: one change, at run
# 3, ratio 0.013 / 0.012341 = 1.0534, no interval and no p; no trend picture of rates.
for i in 1 2 3; do
    v=$(echo "0.01234 0.012341 0.013" | cut -d' ' -f$i)
    cat >"$T/acc$i.json" <<EOF
{"schema": "brdfbench.rows/1", "source": {"schema": "brdfbench.accuracy/1", "kind": "accuracy", "file": "accuracy.json"},
 "context": {"device": "cpu0", "git_revision": "a$i", "date": "2026-05-0${i}T00:00:00Z"},
 "rows": [{"device": "", "model": "fq2", "keys": {"label": "fq2"}, "row": "fq2", "status": "ok",
   "metrics": [{"name": "max_rel", "unit": "1", "direction": "lower", "timed": false, "value": $v}]}]}
EOF
done
"$BIN" history "$T/acc1.json" "$T/acc2.json" "$T/acc3.json" --kind accuracy --out "$T/h_acc" >"$T/out" 2>"$T/err" && ok ||
    bad "history --kind accuracy: $(cat "$T/err")"
"$PY" - "$T/h_acc/history.json" <<'EOF' && ok || bad "history --kind accuracy: history.json"
import json, sys
h = json.load(open(sys.argv[1]))
ch = h["changes"]
assert len(ch) == 1 and ch[0]["label"] == "fq2" and ch[0]["index"] == 3 and ch[0]["commit"] == "a3", ch
assert abs(ch[0]["ratio"] - 0.013 / 0.012341) < 1e-9 and ch[0]["interval"] is None and ch[0]["p"] is None, ch
assert h["rows"][0]["basis"] == "value" and h["rows"][0]["direction"] == "lower"
EOF
[ ! -e "$T/h_acc/history_normalised.png" ] && [ -s "$T/h_acc/history.png" ] && ok || bad "history --kind accuracy: pictures"

# --out: a folder made with its parents; a file there is refused before anything is read.
"$BIN" history "$T/step/run01.json" "$T/step/run02.json" --out "$T/deep/a/b" >/dev/null 2>"$T/err" &&
    [ -s "$T/deep/a/b/history.json" ] && ok || bad "history --out with missing parents: $(cat "$T/err")"
touch "$T/afile"
expect 2 "--out: .*afile is not a folder" history "$T/step/run01.json" "$T/step/run02.json" --out "$T/afile"

# Bad input: one line, exit 2, nothing written.
expect 2 "--db and run folders or files given together" history --db "$T/h.sqlite" "$T/step/run01.json" --out "$T/x1"
expect 2 "holds 1 run of kind throughput \(a history takes 2 or more\)" history "$T/step/run01.json" --out "$T/x2"
expect 2 "no such store" history --db "$T/none.sqlite" --out "$T/x3"
# ... but a store's first run (a CI workflow's first day, docs/ci.md) is no error: a note, exit 0,
# --fail-if-slower included, and no folder written
"$BIN" store add "$T/step/run01.json" --db "$T/one.sqlite" >/dev/null 2>"$T/err" || bad "store add of one run: $(cat "$T/err")"
"$BIN" history --db "$T/one.sqlite" --fail-if-slower 10 --out "$T/x5" >"$T/out" 2>"$T/err" &&
    grep -q "holds 1 run of kind throughput: no series yet" "$T/out" && [ ! -e "$T/x5" ] && ok ||
    bad "history of a store with one run: $(cat "$T/out" "$T/err")"
expect 2 "--fail-if-slower" history "$T/step/run01.json" "$T/step/run02.json" --fail-if-slower -5 --out "$T/x4"
[ ! -e "$T/x1" ] && [ ! -e "$T/x2" ] && [ ! -e "$T/x3" ] && [ ! -e "$T/x4" ] && ok || bad "a refused history wrote its folder"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
