#!/usr/bin/env bash
# test_store.sh - `brdfbench store add|list|export` (host/results/store.c): a run added twice is
# stored once (the content hash); two processes adding different runs at the same time lose
# nothing; the export gives back each stored document as it was; a file that is not an SQLite
# database, another program's database and a damaged store are refused with one line and exit
# 2 or 3, and nothing of a refused add is stored. No device: the runs are rows documents
# written here.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
PY=/usr/bin/python3

# A rows document for run $1 (its date makes each one a different document).
mkrun() {
    mkdir -p "$T/runs/$1"
    cat >"$T/runs/$1/rows.json" <<EOF
{"schema": "brdfbench.rows/1",
 "source": {"schema": "brdfbench.throughput/3", "kind": "throughput", "file": "throughput.json"},
 "context": {"device": "cpu0", "git_revision": "rev$1", "date": "2026-01-01T00:00:$(printf '%02d' $(( $1 % 60 )))Z"},
 "rows": [
  {"device": "", "model": "m1", "keys": {"label": "m1", "variant": "default", "n_mode": "uniform"},
   "row": "m1 | default | n uniform", "status": "ok",
   "metrics": [{"name": "evals_per_s", "unit": "1/s", "direction": "higher", "timed": true, "value": 2e8,
                "min": 1e8, "max": 4e8, "reps": [1e8, 2e8, 4e8]}]},
  {"device": "", "model": "m2", "keys": {"label": "m2", "variant": "default", "n_mode": "uniform"},
   "row": "m2 | default | n uniform", "status": "ok",
   "metrics": [{"name": "evals_per_s", "unit": "1/s", "direction": "higher", "timed": true, "value": 3e8,
                "min": 3e8, "max": 3e8, "reps": [3e8, 3e8, 3e8]}]}
 ]}
EOF
}
for i in $(seq 1 40); do mkrun "$i"; done
DB="$T/h.sqlite"

# Idempotence: the same run twice, and again in a later add, is stored once.
"$BIN" store add "$T/runs/1/rows.json" "$T/runs/2/rows.json" --db "$DB" >"$T/out" 2>"$T/err" && ok || bad "add: $(cat "$T/err")"
grep -q "2 added, 0 already stored" "$T/out" && ok || bad "first add: $(cat "$T/out")"
"$BIN" store add "$T/runs/1/rows.json" --db "$DB" >"$T/out" 2>"$T/err" && ok || bad "add again: $(cat "$T/err")"
grep -q "0 added, 1 already stored" "$T/out" && ok || bad "second add: $(cat "$T/out")"
[ "$("$PY" -c "import sqlite3,sys; print(sqlite3.connect(sys.argv[1]).execute('select count(*) from runs').fetchone()[0])" "$DB")" = 2 ] \
    && ok || bad "runs table does not hold 2 runs"
# two runs of two rows with one metric each: 4 lines of the metrics table
[ "$("$PY" -c "import sqlite3,sys; print(sqlite3.connect(sys.argv[1]).execute('select count(*) from metrics').fetchone()[0])" "$DB")" = 4 ] \
    && ok || bad "metrics table does not hold 4 lines"
[ "$("$PY" -c "import sqlite3,sys; print(sqlite3.connect(sys.argv[1]).execute('pragma journal_mode').fetchone()[0])" "$DB")" = wal ] \
    && ok || bad "the store is not in WAL mode"

# Two writers at once: runs 3..21 and 22..40, one add each, both loops started together.
( for i in $(seq 3 21); do "$BIN" store add "$T/runs/$i/rows.json" --db "$DB" >/dev/null 2>>"$T/err_a" || echo "a$i" >>"$T/lost"; done ) &
pa=$!
( for i in $(seq 22 40); do "$BIN" store add "$T/runs/$i/rows.json" --db "$DB" >/dev/null 2>>"$T/err_b" || echo "b$i" >>"$T/lost"; done ) &
pb=$!
wait $pa $pb
[ ! -s "$T/lost" ] && ok || bad "concurrent adds failed: $(cat "$T/lost") $(head -3 "$T/err_a" "$T/err_b")"
"$BIN" store list --db "$DB" >"$T/list" 2>"$T/err" && ok || bad "list: $(cat "$T/err")"
grep -q ": 40 stored runs" "$T/list" && ok || bad "after the concurrent adds: $(tail -1 "$T/list")"
for i in 1 3 21 22 40; do
    grep -qE " rev$i +2 +" "$T/list" && ok || bad "run $i not listed: $(head -3 "$T/list")"
done

# Two writers at once on a store that is not there yet: both make it (one makes the layout, the
# other waits for it), and both runs land.
"$BIN" store add "$T/runs/1/rows.json" --db "$T/new.sqlite" >/dev/null 2>"$T/err_c" &
pc=$!
"$BIN" store add "$T/runs/2/rows.json" --db "$T/new.sqlite" >/dev/null 2>"$T/err_d" &
pd=$!
wait $pc && wait $pd && ok || bad "two first adds at once: $(cat "$T/err_c" "$T/err_d")"
"$BIN" store list --db "$T/new.sqlite" 2>&1 | grep -q ": 2 stored runs" && ok || bad "two first adds at once: not 2 runs"

# Export: each stored document back as a rows document with the same rows.
"$BIN" store export --db "$DB" --out "$T/exp" >"$T/out" 2>"$T/err" && ok || bad "export: $(cat "$T/err")"
[ "$(ls "$T/exp" | wc -l)" = 40 ] && ok || bad "export wrote $(ls "$T/exp" | wc -l) files, expected 40"
"$PY" - "$T" <<'EOF' && ok || bad "exported documents differ from the added ones"
import json, sys, glob
T = sys.argv[1]
by_rev = {}
for f in glob.glob(T + "/exp/*.rows.json"):
    d = json.load(open(f))
    by_rev[d["context"]["git_revision"]] = d
assert len(by_rev) == 40, len(by_rev)
for i in range(1, 41):
    src = json.load(open("%s/runs/%d/rows.json" % (T, i)))
    got = by_rev["rev%d" % i]
    assert got["schema"] == "brdfbench.rows/1" and got["source"]["kind"] == "throughput"
    assert [r["row"] for r in got["rows"]] == [r["row"] for r in src["rows"]]
    for a, b in zip(got["rows"], src["rows"]):
        assert a["metrics"][0]["reps"] == b["metrics"][0]["reps"], (a, b)
EOF

# Refusals: one line, exit 2 for a file that is not a store, 3 for a damaged store.
echo "not a database at all, just text that is long enough to be read as a header" >"$T/text.sqlite"
expect 2 "text.sqlite: not an SQLite database" store list --db "$T/text.sqlite"
expect 2 "text.sqlite: not an SQLite database" store add "$T/runs/1/rows.json" --db "$T/text.sqlite"
"$PY" -c "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); c.execute('create table t(x)'); c.commit()" "$T/other.sqlite"
expect 2 "other.sqlite: an SQLite database of another program \(application_id 0x0" store add "$T/runs/1/rows.json" --db "$T/other.sqlite"
"$PY" -c "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); c.execute('create table t(x)'); c.execute('pragma application_id=1145258561'); c.commit()" "$T/other2.sqlite"
expect 2 "an SQLite database of another program \(application_id 0x4443" store list --db "$T/other2.sqlite"
expect 2 "nothere.sqlite: no such store" store list --db "$T/nothere.sqlite"
[ ! -e "$T/nothere.sqlite" ] && ok || bad "list made a store"
# a damaged store: a copy with its pages after the first overwritten
cp "$DB" "$T/damaged.sqlite"
"$PY" -c "import sqlite3,sys; sqlite3.connect(sys.argv[1]).execute('pragma wal_checkpoint(TRUNCATE)')" "$T/damaged.sqlite"
rm -f "$T/damaged.sqlite-wal" "$T/damaged.sqlite-shm"
"$PY" -c "
import sys
f = open(sys.argv[1], 'r+b'); f.seek(4096); f.write(b'\xff' * 8192); f.close()" "$T/damaged.sqlite"
"$BIN" store list --db "$T/damaged.sqlite" >"$T/out" 2>"$T/err"
rc=$?
{ [ $rc -eq 3 ] || [ $rc -eq 2 ]; } && [ "$(wc -l <"$T/err")" -eq 1 ] && grep -q "damaged.sqlite" "$T/err" && ok ||
    bad "damaged store: exit $rc: $(cat "$T/err")"
# a rows document naming a kind that is none of the kinds (a path, here) is refused
sed 's/"kind": "throughput"/"kind": "..\/..\/evil"/' "$T/runs/1/rows.json" >"$T/evil.json"
expect 2 "evil.json: a document of kind '../../evil' \(accepted: throughput, accuracy" store add "$T/evil.json" --db "$T/evil.sqlite"
# and a store whose kind column holds one (written by another program) exports under a plain name
cp "$DB" "$T/edited.sqlite"
"$PY" -c "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); c.execute(\"update runs set kind='../../evil' where id=1\"); c.commit()" "$T/edited.sqlite"
"$BIN" store export --db "$T/edited.sqlite" --out "$T/exp2" >/dev/null 2>"$T/err" && [ -f "$T/exp2/1-other.rows.json" ] &&
    [ ! -e "$T/evil.rows.json" ] && ok || bad "export of an edited kind: $(cat "$T/err"; ls "$T/exp2" | head -3)"
# a bad input among good ones adds nothing
echo '{' >"$T/broken.json"
expect 2 "broken.json" store add "$T/runs/1/rows.json" "$T/broken.json" --db "$T/fresh.sqlite"
[ ! -e "$T/fresh.sqlite" ] && ok || bad "a refused add made the store"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
