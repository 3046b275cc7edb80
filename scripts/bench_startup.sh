#!/usr/bin/env bash
# bench_startup.sh - how long the commands that open no device and draw nothing take, start-up
# included (loading the binary and its shared libraries): the median wall time of REPS runs each
# of `version`, `help`, `rows RUN`, `report RUN` and `compare RUN RUN --json -`, in milliseconds.
# A benchmark, never a test: its figures go into notes, not into assertions.
#
#   scripts/bench_startup.sh [BRDFBENCH] [REPS] [RUN_DIR]   (defaults: build/brdfbench, 20)
#
# RUN_DIR is a run folder of `brdfbench all` for rows, report and compare to read; without one the
# script makes one first (`all --quick --models fq2`, which needs an OpenCL device; not timed).
# report writes into a scratch copy of the folder, so RUN_DIR is never changed.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/brdfbench}
reps=${2:-20}
run=${3:-}
[ -x "$bin" ] || { echo "bench_startup: $bin is not an executable (build first)" >&2; exit 2; }
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
if [ -z "$run" ]; then
    run="$W/R"
    "$bin" all --quick --models fq2 --out "$run" --quiet >/dev/null 2>&1 ||
        { echo "bench_startup: 'all --quick --models fq2' failed; give a run folder as the third argument" >&2; exit 2; }
fi
cp -r "$run" "$W/copy"
# Each command must succeed, or its time would be that of an error message.
for args in "version" "help" "rows $run" "report $W/copy" "compare $run $run --json -"; do
    # shellcheck disable=SC2086
    "$bin" $args >/dev/null 2>"$W/err" || { echo "bench_startup: '$args' failed: $(head -c 300 "$W/err")" >&2; exit 1; }
done

# The median of REPS wall times of one command line, in ms (bash's EPOCHREALTIME around the
# process: fork, exec, dynamic loading and the command itself).
median_ms() {
    local i t0 t1 times=()
    for ((i = 0; i < reps; i++)); do
        t0=$EPOCHREALTIME
        "$@" >/dev/null 2>&1 || true
        t1=$EPOCHREALTIME
        times+=("$(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.3f", (b - a) * 1000}')")
    done
    printf '%s\n' "${times[@]}" | sort -g | awk '{a[NR] = $1} END {m = (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2; printf "%.1f", m}'
}

echo "binary: $bin ($(ldd "$bin" | wc -l) shared libraries; $(ldd "$bin" | grep -c opencv || true) of OpenCV)"
printf '%-28s %s\n' "command" "median ms of $reps"
printf '%-28s %s\n' "version" "$(median_ms "$bin" version)"
printf '%-28s %s\n' "help" "$(median_ms "$bin" help)"
printf '%-28s %s\n' "rows RUN" "$(median_ms "$bin" rows "$run")"
printf '%-28s %s\n' "report RUN" "$(median_ms "$bin" report "$W/copy")"
printf '%-28s %s\n' "compare RUN RUN --json -" "$(median_ms "$bin" compare "$run" "$run" --json -)"
printf '%-28s %s\n' "/bin/true (process cost)" "$(median_ms /bin/true)"
