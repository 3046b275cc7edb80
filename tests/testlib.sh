# testlib.sh - the counters and the exit-code-and-message check that the shell tests share.
# Sourced by a test after it sets BIN (the brdfbench binary) and T (its temporary folder); the
# test prints "$pass passed, $fail failed" at its end and exits non-zero when fail > 0.
pass=0 fail=0

# brdf_test_init: BIN (the brdfbench binary, from $BRDFBENCH), SRC (the source tree, from
# $SRC_DIR) and T, a temporary folder removed when the test exits (write permission given back
# first, for the tests that take it away), or kept to be looked at when KEEP is set.
brdf_test_init() {
    BIN=${BRDFBENCH:?BRDFBENCH must name the brdfbench binary}
    SRC=${SRC_DIR:?SRC_DIR must name the source tree}
    T=$(mktemp -d)
    trap '[ -n "${KEEP:-}" ] || { chmod -R u+w "$T"; rm -rf "$T"; }' EXIT
}
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }

# expect CODE PATTERN ARGS... : exit code and a stderr line matching PATTERN
expect() {
    local code=$1 pattern=$2
    shift 2
    "$BIN" "$@" >"$T/out" 2>"$T/err"
    local rc=$?
    if [ "$rc" -ne "$code" ]; then bad "$* -> exit $rc, expected $code: $(head -c 400 "$T/err")"; return; fi
    if ! grep -qE -- "$pattern" "$T/err"; then bad "$* -> message '$(head -c 400 "$T/err")' lacks /$pattern/"; return; fi
    ok
}

# jsoncheck CHECK FILE [ARGS...]: the named check of tests/jsoncheck.py on FILE; its exit status
# (a failure prints the check's name, the file and what differed). Used as `jsoncheck ... && ok
# || bad "what"`.
BRDF_JSONCHECK="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/jsoncheck.py"
jsoncheck() {
    python3 "$BRDF_JSONCHECK" "$@"
}

# value FILE PYTHON-EXPRESSION: the expression over r, the first hemisphere row of an
# accuracy.json, and h = r['hemisphere'] (None where there is none); holds FILE CONDITION WHAT:
# ok when the condition is True, else a failure naming WHAT and what it gave.
value() {
    python3 -c "
import json, sys, math
d = json.load(open(sys.argv[1]))
rows = [x for x in d['results'] if x.get('sweep') == 'hemisphere']
r = rows[0] if rows else None
h = r['hemisphere'] if r else None
print($2)" "$1"
}
holds() {
    local v
    v=$(value "$1" "$2" 2>&1)
    if [ "$v" = "True" ]; then ok; else bad "$3: $2 -> $v"; fi
}

# rows_both_ways FILE NOW PREV CHECK: FILE carries its rows under schema NOW; its rows, and those
# of the same file as version PREV wrote it (the rows member taken out, so read by PREV's layout
# through its upgrade function), are each what `python3 CHECK FILE ROWS_JSON` accepts (the test's
# second writing of the rows from the layout), and the two readings give the same rows.
rows_both_ways() {
    local file=$1 now=$2 prev=$3 check=$4 base
    base=$(basename "$file" .json)
    python3 - "$file" "$now" "$prev" "$T/$base.prev.json" <<'PY' && ok || bad "$file: not a $now file with its rows"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["schema"] == sys.argv[2] and d["rows"]["rows"], d["schema"]
del d["rows"]
d["schema"] = sys.argv[3]
json.dump(d, open(sys.argv[4], "w"))
PY
    "$BIN" rows "$file" --format json --output "$T/$base.rows.json" 2>"$T/err" && ok || bad "rows $file: $(cat "$T/err")"
    "$BIN" rows "$T/$base.prev.json" --format json --output "$T/$base.prev.rows.json" 2>"$T/err" && ok ||
        bad "rows $file as $prev: $(cat "$T/err")"
    python3 "$check" "$file" "$T/$base.rows.json" && ok || bad "$file: its rows member differs from its layout's"
    python3 - "$T/$base.rows.json" "$T/$base.prev.rows.json" <<'PY' && ok || bad "$file: the rows member and the upgrade read differently"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert a["rows"] == b["rows"], (a["rows"], b["rows"])
PY
}
