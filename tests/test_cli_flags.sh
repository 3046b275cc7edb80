#!/usr/bin/env bash
# test_cli_flags.sh - one meaning per flag and conventional output: every flag that --help
# shows is one the parser takes; a flag shared by several commands reads the same in each
# --help; --version after any command; --json - / --csv - put one document on standard
# output; list --json; a model given twice is measured once; --quiet prints nothing.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
cd "$T" || exit 1

# every command the dispatcher lists
COMMANDS=$("$BIN" --help | awk '/^  [a-z]/ { print $1 }' | tr '\n' ' ')
case " $COMMANDS " in *" accuracy "*" version "*) ok ;; *) bad "brdfbench --help lists no commands: $COMMANDS" ;; esac

# 1. Each command's --help is made from its flag table: every flag shown there is accepted.
#    "--flag=V" followed by an unknown flag: when the first is a flag of the command, the
#    parser gets past it (or refuses its value) and the message is never "unknown option
#    '--flag'". --model-file=V and --kernel-dir=V fail on reading V before anything runs.
#    (Each flag name is tried with the first command that shows it, to keep this quick; a
#    shared flag comes from one definition in host/cli/cli_table.h.)
seen=" "
for c in $COMMANDS; do
    "$BIN" "$c" --help >"$T/help_$c" 2>&1 || bad "$c --help exits non-zero"
    grep -qE '^  --help, -h ' "$T/help_$c" && grep -qE '^  --version ' "$T/help_$c" && ok \
        || bad "$c --help lacks --help or --version"
    for f in $(grep -oE '^  --[a-z0-9-]+' "$T/help_$c" | sort -u); do
        case "$f" in --help|--version) continue ;; esac
        case "$seen" in *" $f "*) continue ;; esac
        seen="$seen$f "
        "$BIN" "$c" "$f=V" --no-such-flag-at-all >/dev/null 2>"$T/err"
        if grep -q "unknown option '$f" "$T/err"; then bad "$c --help shows $f but the parser refuses it"; else ok; fi
    done
done

# 2. A flag that several commands take has one meaning: its help entry (continuation lines
#    joined, the closing "(accepted values; default)" left out, since defaults may differ)
#    is the same text in every command's --help.
jsoncheck cli_flags_help_flags_read_alike "$T" $COMMANDS && ok || bad "a flag reads differently in two commands' --help"

# 3. --version after any command, and `brdfbench version`: the same one line.
"$BIN" version >"$T/v0" 2>&1 && [ "$(wc -l <"$T/v0")" -eq 1 ] && grep -qE '^brdfbench [0-9]+\.[0-9]+' "$T/v0" && ok \
    || bad "brdfbench version: $(cat "$T/v0")"
for c in $COMMANDS; do
    "$BIN" "$c" --version >"$T/v1" 2>&1 && cmp -s "$T/v0" "$T/v1" && ok || bad "$c --version: $(cat "$T/v1")"
done
"$BIN" accuracy --n-min 2 --version >"$T/v1" 2>&1 && cmp -s "$T/v0" "$T/v1" && ok || bad "--version after other flags"

# 4. list --json -: one JSON document on standard output whose models are the listing's
#    (counted independently from the text form: one "  id  description" line per model).
"$BIN" list --json - >"$T/list.json" 2>"$T/err" && ok || bad "list --json -: $(cat "$T/err")"
"$BIN" list >"$T/list.txt" 2>&1
jsoncheck cli_flags_list_json_as_list "$T/list.json" "$T/list.txt" && ok || bad "list --json - differs from list"
"$BIN" list --json "$T/list2.json" >"$T/out" 2>&1 && cmp -s "$T/list.json" "$T/list2.json" && [ ! -s "$T/out" ] && ok \
    || bad "list --json FILE differs from list --json -"

# The rest needs an OpenCL device.
if ! python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if any(p["devices"] for p in d["platforms"]) else 1)' "$T/list.json"; then
    echo "$pass passed, $fail failed; SKIP: no OpenCL device for the checks that run kernels"
    [ "$fail" -eq 0 ] && exit 77 || exit 1
fi
GRID=(--n-min 2 --n-max 6 --samples 16)

# 5. --json - and --csv -: the document alone on standard output (no table, no folder).
"$BIN" accuracy --models fq2,cq2 "${GRID[@]}" --json - >"$T/acc.json" 2>"$T/err" && ok || bad "accuracy --json -: $(cat "$T/err")"
jsoncheck cli_flags_accuracy_json_stdout_alone "$T/acc.json" && ok || bad "accuracy --json - is not the accuracy document alone"
[ ! -e results ] && ok || bad "accuracy --json - without --out made a run folder"
"$BIN" accuracy --models fq2 "${GRID[@]}" --csv - >"$T/acc.csv" 2>"$T/err" && ok || bad "accuracy --csv -: $(cat "$T/err")"
# the CSV alone: a header, then one row per n of the grid (2..6: 5 rows), all of fq2
jsoncheck cli_flags_accuracy_csv_stdout_alone "$T/acc.csv" && ok || bad "accuracy --csv - is not the CSV alone: $(head -3 "$T/acc.csv")"
"$BIN" accuracy --models fq2 "${GRID[@]}" --json "$T/f.json" --out "$T/both" >/dev/null 2>"$T/err" \
    && [ -s "$T/f.json" ] && [ -s "$T/both/accuracy.json" ] && [ -s "$T/both/accuracy.csv" ] && ok \
    || bad "accuracy --json FILE --out DIR must write both: $(cat "$T/err")"
"$BIN" fit "${GRID[@]}" --json - >"$T/fit.json" 2>"$T/err" && [ ! -e results ] \
    && python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["schema"].startswith("brdfbench.fit/"), d["schema"]' "$T/fit.json" \
    && ok || bad "fit --json -: the document alone, no folder: $(cat "$T/err")"
"$BIN" throughput --models fq2 --variants default --n-modes uniform --no-sweep --no-host-c --reps 1 --min-time 0.001 \
    --csv - >"$T/tp.csv" 2>"$T/err" && [ ! -e results ] && ok || bad "throughput --csv -: $(cat "$T/err")"
# the CSV alone: a header and one row per model, pow() (every run's reference row) and fq2
jsoncheck cli_flags_throughput_csv_stdout_alone "$T/tp.csv" && ok || bad "throughput --csv - is not the CSV alone: $(cat "$T/tp.csv")"
printf '{"gates":[{"model":"fq2","metric":"whole.max_abs","n_min":2,"n_max":6,"samples":16,"max":1}]}' >gates.json
"$BIN" gate gates.json --json - >"$T/gate.json" 2>"$T/err" && ok || bad "gate --json -: $(cat "$T/err")"
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["gates"][0]["status"] == "pass", d' "$T/gate.json" \
    && grep -q '^PASS  ' "$T/err" && ok || bad "gate --json -: the document on stdout, the gate lines on stderr"

# 6. A model given twice (the same label, the same NAME=EXPR, the same file by two paths) is
#    measured once, with a note; its figures are those of one run.
"$BIN" accuracy --models fq2,cq2,fq2 "${GRID[@]}" --json - >"$T/dup.json" 2>"$T/err" && ok || bad "fq2 twice: $(cat "$T/err")"
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert [r["label"] for r in d["results"]] == ["fq2","cq2"], d["results"]' \
    "$T/dup.json" && grep -q "note: --models: fq2 given twice, measured once" "$T/err" && ok || bad "fq2,cq2,fq2 must give fq2, cq2"
# fq with its default Q is the same model as fq:Q=0.64 (list: fq's default Q is 0.64)
"$BIN" accuracy --models fq,fq:Q=0.64 "${GRID[@]}" --json - >"$T/dup2.json" 2>"$T/err"
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert len(d["results"]) == 1, d["results"]' "$T/dup2.json" \
    && ok || bad "fq and fq:Q=0.64 are one model: $(cat "$T/err")"
"$BIN" accuracy --model 'z=c*c' --model 'z=c*c' "${GRID[@]}" --json - >"$T/dup3.json" 2>"$T/err"
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert [r["label"] for r in d["results"]] == ["z"], d["results"]' \
    "$T/dup3.json" && grep -q "note: --model z: given twice with the same expression" "$T/err" && ok \
    || bad "--model z=c*c twice: $(cat "$T/err")"
mkdir -p sub && cp "$SRC/tests/test_usermodel_files/scaled.cl" sub/
"$BIN" accuracy --model-file sub/scaled.cl --model-file ./sub/../sub/scaled.cl "${GRID[@]}" --json - >"$T/dup4.json" 2>"$T/err"
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert len(d["results"]) == 1, d["results"]' "$T/dup4.json" \
    && grep -q "note: --model-file ./sub/../sub/scaled.cl: the same file as sub/scaled.cl, read once" "$T/err" && ok \
    || bad "one model file by two paths: $(cat "$T/err")"

# 7. --quiet: nothing on stdout or stderr from a run that succeeds, and its files written.
"$BIN" accuracy --models fq2 "${GRID[@]}" --out "$T/q" --quiet >"$T/out" 2>"$T/err" && [ ! -s "$T/out" ] && [ ! -s "$T/err" ] \
    && [ -s "$T/q/accuracy.json" ] && ok || bad "accuracy --quiet printed: $(cat "$T/out" "$T/err")"
"$BIN" gate gates.json --quiet >"$T/out" 2>"$T/err" && [ ! -s "$T/out" ] && [ ! -s "$T/err" ] && ok \
    || bad "gate --quiet on a passing gate printed: $(cat "$T/out" "$T/err")"
# a failing gate is still named (a bound no max Delta can meet: Delta >= 0)
printf '{"gates":[{"model":"fq2","metric":"whole.max_abs","n_min":2,"n_max":6,"samples":16,"max":-1}]}' >fail.json
"$BIN" gate fail.json --quiet >"$T/out" 2>"$T/err"
rc=$?
[ $rc -eq 1 ] && [ "$(grep -c '^FAIL  ' "$T/out")" -eq 1 ] && [ "$(wc -l <"$T/out")" -eq 1 ] && ok \
    || bad "gate --quiet on a failing gate: exit $rc, stdout: $(cat "$T/out")"

# 8. all takes the grid flags: they set the main sweep and the heatmaps' range of n (over the
#    --quick defaults), and --quiet leaves nothing on the terminal but warnings.
"$BIN" all --quick --models fq2 --n-min 3 --n-max 40 --n-step 1 --samples 32 --out "$T/all" --quiet >"$T/out" 2>"$T/err"
rc=$?
# (warnings may remain: the frontier step measures every lobe approximation, whatever --models says)
[ $rc -eq 0 ] && [ ! -s "$T/out" ] && ! grep -qv 'warning' "$T/err" && ok || bad "all --quiet with grid flags: exit $rc: $(cat "$T/out" "$T/err")"
jsoncheck cli_flags_all_applies_grid_flags "$T/all" && ok || bad "all did not apply the grid flags"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
