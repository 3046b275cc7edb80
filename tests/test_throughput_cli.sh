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
jsoncheck throughput_cli_throughput_contract "$T/run/throughput.json" && ok || bad "throughput.json contract"
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
jsoncheck throughput_cli_failed_variant_rows "$T/broken/throughput.json" && ok || bad "failed variant rows"

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
jsoncheck throughput_cli_ab_options_two_sides "$T/ab" && ok || bad "--ab-options: the two sides"
"$BIN" compare "$T/ab/ab/a" "$T/ab/ab/b" --out "$T/abc" --quiet 2>"$T/err" && ok || bad "compare of the A/B sides: $(cat "$T/err")"
expect 2 "--variants: ab is the variant of --ab-options OPTIONS" throughput --variants default,ab --out "$T/x11"
expect 2 "--ab-options: expected OpenCL build options" throughput --ab-options "" --out "$T/x12"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
