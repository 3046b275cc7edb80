#!/usr/bin/env bash
# bench_compare.sh - how often `brdfbench compare` calls a change where there is none, and how
# often it sees one that is there: the identical-runs (A/A) experiment and the planted slowdown.
#
#   bash scripts/bench_compare.sh [PAIRS]          (default 5 pairs per condition)
#
# Conditions, PAIRS pairs of throughput runs each (the same binary, the same flags):
#   aa        two runs one after the other, nothing changed;
#   aa-load   the same with a CPU-bound process (a shell loop) running during the second run;
#   planted   the second run's user lobe replaced by the same lobe with about twice the work
#             (tests/ci/mylobe_2x.cl under the name of tests/ci/mylobe.cl).
# Each pair is compared twice: with compare's defaults (--alpha 0.05, 5% threshold) and with
# docs/ci.md's settings (--fail-if-slower 10 --holm). Printed per condition and setting: the
# share of rows called faster or slower (the false alarms; the planted lobe's rows excepted)
# and, for planted, the share of the lobe's rows called slower (the detections).
#
# Environment: BRDFBENCH (the binary; default build/brdfbench), TP_FLAGS (the throughput flags;
# default below), MODELS (default: throughput's default set), COMPARE_SETS ("default ci", or "default" for a binary whose compare has no
# --holm), CONDITIONS (default "aa aa-load planted"), KEEP=1 to keep the runs. A benchmark, not a test: its figures go into notes, never
# into assertions.
set -euo pipefail
cd "$(dirname "$0")/.."
B=${BRDFBENCH:-build/brdfbench}
PAIRS=${1:-5}
TP_FLAGS=${TP_FLAGS:---reps 10 --variants default --no-host-c --no-sweep --quiet}
SETS=${COMPARE_SETS:-default ci}
CONDS=${CONDITIONS:-aa aa-load planted}
# the default set of `brdfbench throughput` (model_spec_list_default), named, and the user lobe
MODELS=${MODELS:-phong,blinn,cq2,fvol,fvol64,schlick,lyon:k=2,fq:Q=0.64,fq2,fq2n,phongn,blinnn,beckmann,ggx,phongpow}
W=$(mktemp -d)
[ -n "${KEEP:-}" ] || trap 'rm -rf "$W"' EXIT

hog_pid=
hog_start() { (while :; do :; done) & hog_pid=$!; }
hog_stop() { [ -n "$hog_pid" ] && kill "$hog_pid" 2>/dev/null; wait "$hog_pid" 2>/dev/null || true; hog_pid=; }
trap 'hog_stop' INT TERM

run() {   # OUT LOBE_FILE [hog]
    local out=$1 lobe=$2
    [ "${3:-}" = hog ] && hog_start
    "$B" throughput $TP_FLAGS --models "$MODELS,mylobe" --model-file "tests/ci/$lobe" --out "$out" >/dev/null
    hog_stop
}

compare_flags() {
    case $1 in
        default) echo "" ;;
        ci) echo "--fail-if-slower 10 --holm" ;;
    esac
}

# counts "FLAGGED ROWS PLANTED_SLOWER PLANTED_ROWS" of one comparison's compare.csv (COND
# planted: the lobe's rows are the planted ones; otherwise they are rows like any other)
count() {
    python3 - "$1" "$2" <<'PY'
import csv, sys
flagged = rows = ps = pr = 0
for r in csv.DictReader(open(sys.argv[1])):
    # the rates only: the rows of other figures (a model's accuracy check beside its rate) are
    # no speed and are never called faster or slower
    if r["kind"] != "throughput" or r["verdict"] == "baseline" or r["key"].startswith("peak") or r["sense"] != "speed":
        continue
    if sys.argv[2] == "planted" and r["key"].startswith("mylobe |"):
        pr += 1
        ps += r["verdict"] == "slower"
    else:
        rows += 1
        flagged += r["verdict"] in ("faster", "slower")
print(flagged, rows, ps, pr)
PY
}

declare -A F R S P
for cond in $CONDS; do
    for set in $SETS; do F[$cond.$set]=0 R[$cond.$set]=0 S[$cond.$set]=0 P[$cond.$set]=0; done
    for i in $(seq 1 "$PAIRS"); do
        a=$W/$cond-$i-a b=$W/$cond-$i-b
        run "$a" mylobe.cl
        case $cond in
            aa) run "$b" mylobe.cl ;;
            aa-load) run "$b" mylobe.cl hog ;;
            planted) run "$b" mylobe_2x.cl ;;
        esac
        for set in $SETS; do
            "$B" compare "$a" "$b" --out "$W/c-$cond-$i-$set" --quiet $(compare_flags "$set") >/dev/null 2>&1 || true
            read -r f r s p <<<"$(count "$W/c-$cond-$i-$set/compare.csv" "$cond")"
            F[$cond.$set]=$((F[$cond.$set] + f)) R[$cond.$set]=$((R[$cond.$set] + r))
            S[$cond.$set]=$((S[$cond.$set] + s)) P[$cond.$set]=$((P[$cond.$set] + p))
            echo "$cond pair $i, $set: $f of $r rows flagged; planted lobe slower in $s of $p" >&2
        done
    done
done

echo "brdfbench $("$B" --version 2>/dev/null | head -1), $PAIRS pairs per condition, throughput $TP_FLAGS"
printf '%-9s %-8s %16s %22s\n' condition compare "false alarms" "planted rows slower"
for cond in $CONDS; do
    for set in $SETS; do
        f=${F[$cond.$set]} r=${R[$cond.$set]} s=${S[$cond.$set]} p=${P[$cond.$set]}
        share=$(python3 -c "print('%d/%d = %.1f%%' % ($f, $r, 100.0 * $f / $r) if $r else '-')")
        det=$(python3 -c "print('%d/%d' % ($s, $p) if $p and '$cond' == 'planted' else '-')")
        printf '%-9s %-8s %16s %22s\n' "$cond" "$set" "$share" "$det"
    done
done
