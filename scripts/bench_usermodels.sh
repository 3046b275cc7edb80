#!/usr/bin/env bash
# bench_usermodels.sh - what a user model costs against the same formula as a built-in model.
#
# The user model sq = fmax(0.45 n (c-1) + 1, 0)^2 is the built-in quad:a=0.45,b=0 written a
# second time as a --model expression, so both runs do the same work. For accuracy (the
# default grid, n in [2, 1000]), a gate over n in [2, 200] and `all --quick`, the script
# runs each side REPEATS times (alternating), and prints the median wall time of each side and
# their ratio (user / built-in). A benchmark, not a test: it asserts nothing.
#
#   scripts/bench_usermodels.sh [BRDFBENCH] [REPEATS]     (defaults: build/brdfbench, 5)
#   BENCH_ONLY="accuracy gate" scripts/bench_usermodels.sh  runs a subset
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/brdfbench}
repeats=${2:-5}
only=${BENCH_ONLY:-"accuracy gate all"}
[ -x "$bin" ] || { echo "bench_usermodels: $bin is not an executable (build first)" >&2; exit 2; }

expr='fmax(0.45*n*(c-1)+1,0)*fmax(0.45*n*(c-1)+1,0)'
builtin='quad:a=0.45,b=0'
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

cat >"$tmp/gate_builtin.json" <<JSON
{"schema": "brdfbench.gates/1", "gates": [
 {"model": "$builtin", "metric": "epicentre.max_rel", "n_min": 2, "n_max": 200, "max": 1},
 {"model": "$builtin", "metric": "whole.max_abs", "n_min": 2, "n_max": 200, "max": 1}]}
JSON
cat >"$tmp/gate_user.json" <<JSON
{"schema": "brdfbench.gates/1", "gates": [
 {"model": "sq", "expression": "$expr", "metric": "epicentre.max_rel", "n_min": 2, "n_max": 200, "max": 1},
 {"model": "sq", "metric": "whole.max_abs", "n_min": 2, "n_max": 200, "max": 1}]}
JSON

# Wall seconds of one command (its output goes to $tmp/log; a failure stops the benchmark).
timed() {
  local t0 t1
  t0=$(date +%s.%N)
  if ! "$@" >"$tmp/log" 2>&1; then
    echo "bench_usermodels: failed: $*" >&2
    tail -5 "$tmp/log" >&2
    exit 3
  fi
  t1=$(date +%s.%N)
  echo "$t0 $t1" | awk '{ printf "%.3f\n", $2 - $1 }'
}
median() { sort -g | awk '{ v[NR] = $1 } END { if (NR % 2) print v[(NR + 1) / 2]; else printf "%.3f\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

run_case() {   # name, then the built-in command and the user command separated by --
  local name=$1; shift
  local -a a=() b=()
  while [ "$1" != "--" ]; do a+=("$1"); shift; done
  shift
  b=("$@")
  : >"$tmp/t_builtin"; : >"$tmp/t_user"
  for ((r = 1; r <= repeats; ++r)); do
    rm -rf "$tmp/out"
    timed "${a[@]}" >>"$tmp/t_builtin"
    rm -rf "$tmp/out"
    timed "${b[@]}" >>"$tmp/t_user"
    echo "bench_usermodels: $name: run $r of $repeats done" >&2
  done
  local mb mu
  mb=$(median <"$tmp/t_builtin")
  mu=$(median <"$tmp/t_user")
  printf '%-10s %12s %12s %8s\n' "$name" "$mb" "$mu" "$(awk -v u="$mu" -v b="$mb" 'BEGIN { printf "%.2f", u / b }')"
}

echo "brdfbench: $("$bin" --version 2>/dev/null | head -1 || true); $repeats runs per side; medians of wall seconds"
printf '%-10s %12s %12s %8s\n' "command" "built-in s" "user s" "ratio"
for what in $only; do
  case $what in
    accuracy)
      run_case accuracy "$bin" accuracy --models "$builtin" --quiet --out "$tmp/out" -- \
        "$bin" accuracy --model "sq=$expr" --quiet --out "$tmp/out" ;;
    gate)
      run_case gate "$bin" gate "$tmp/gate_builtin.json" --quiet -- \
        "$bin" gate "$tmp/gate_user.json" --quiet ;;
    all)
      run_case "all-quick" "$bin" all --quick --models "$builtin" --out "$tmp/out" -- \
        "$bin" all --quick --model "sq=$expr" --models sq --out "$tmp/out" ;;
    *) echo "bench_usermodels: unknown case '$what' (accepted: accuracy gate all)" >&2; exit 2 ;;
  esac
done
