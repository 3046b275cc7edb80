#!/usr/bin/env bash
# test_rusticl.sh - brdfbench on a second OpenCL implementation: Mesa's rusticl on llvmpipe
# (mesa-opencl-icd, RUSTICL_ENABLE=llvmpipe), with a Mesa shader cache of its own (cold):
#   - accuracy of two models gives PoCL's figures to 4 significant digits (each figure of
#     accuracy.json against the same run on PoCL), or flags the model device_disagrees;
#   - throughput runs there (one program per model, the scalar kernels) with every row measured;
#   - --device all over PoCL's pthread and basic devices (POCL_DEVICES) and rusticl: three
#     devices in one run, each with its own context, laid side by side by compare.
# Where rusticl is absent the test says so and is skipped (exit 77); CI installs it.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
export RUSTICL_ENABLE=llvmpipe MESA_SHADER_CACHE_DIR="$T/mesa-cache"
mkdir -p "$MESA_SHADER_CACHE_DIR"

P=$("$BIN" list 2>/dev/null | sed -n 's/^  platform \([0-9]*\): rusticl.*/\1/p' | head -1)
if [ -z "$P" ] || ! "$BIN" list 2>/dev/null | grep -A1 "platform $P: rusticl" | grep -q "device 0: llvmpipe"; then
    echo "rusticl with llvmpipe is not installed here (apt-get install mesa-opencl-icd): skipped"
    echo "0 passed, 0 failed, 1 skipped"
    exit 77
fi

ACC=(accuracy --models fq2,lyon --n-max 30 --samples 256 --quiet)
"$BIN" "${ACC[@]}" --out "$T/pocl" 2>"$T/err" && ok || bad "accuracy on PoCL: $(cat "$T/err")"
"$BIN" "${ACC[@]}" --platform "$P" --out "$T/rusticl" 2>"$T/err" && ok || bad "accuracy on rusticl: $(cat "$T/err")"
jsoncheck rusticl_figures_against_pocl "$T/pocl/accuracy.json" "$T/rusticl/accuracy.json" && ok || bad "rusticl's figures against PoCL's"

TP=(throughput --models fq2,cq2 --reps 2 --min-time 0.002 --work-items 8 --variants default --no-host-c --no-sweep --quiet)
"$BIN" "${TP[@]}" --platform "$P" --out "$T/tp" 2>"$T/err" && ok || bad "throughput on rusticl: $(cat "$T/err")"
jsoncheck rusticl_throughput_on_rusticl_every_row "$T/tp/throughput.json" && ok || bad "throughput on rusticl: every row measured, the scalar kernels"

POCL_DEVICES="pthread basic" "$BIN" "${TP[@]}" --device all --out "$T/all" 2>"$T/err" && ok ||
    bad "--device all over three devices: $(cat "$T/err")"
jsoncheck rusticl_device_all_three_devices "$T/all/throughput.json" && ok || bad "--device all: three devices, each with its own context"
"$BIN" compare "$T/all" --out "$T/allc" --quiet 2>"$T/err" && ok || bad "compare of the three devices: $(cat "$T/err")"
jsoncheck rusticl_compare_three_drivers "$T/allc/compare.json" && ok || bad "compare lays the three drivers side by side"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
