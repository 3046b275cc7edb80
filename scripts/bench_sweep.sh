#!/bin/bash
# bench_sweep.sh - the accuracy sweep's speed, two kernel folders interleaved (a benchmark,
# never a test): prints the median G points/s of each over REPS runs of
#   brdfbench accuracy --models fvol --samples 32768
# usage: scripts/bench_sweep.sh KERNEL_DIR_A KERNEL_DIR_B [REPS]   (default 7)
set -euo pipefail
B=${BRDFBENCH:-build/brdfbench}
A=$1; Bk=$2; REPS=${3:-7}
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
rate() { "$B" accuracy --models fvol --samples 32768 --kernel-dir "$1" --out "$out/r" 2>/dev/null |
         sed -n 's/.*(\([0-9.e+]*\) G points\/s.*/\1/p'; }
ra=(); rb=()
for i in $(seq "$REPS"); do ra+=("$(rate "$A")"); rb+=("$(rate "$Bk")"); done
med() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
ma=$(med "${ra[@]}"); mb=$(med "${rb[@]}")
echo "A $A: median $ma G points/s (${ra[*]})"
echo "B $Bk: median $mb G points/s (${rb[*]})"
awk -v a="$ma" -v b="$mb" 'BEGIN {printf "B / A = %.2f\n", b / a}'
