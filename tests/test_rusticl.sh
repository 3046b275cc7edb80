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
python3 - "$T/pocl/accuracy.json" "$T/rusticl/accuracy.json" <<'PY' && ok || bad "rusticl's figures against PoCL's"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert "llvmpipe" in b["context"]["device"], b["context"]["device"]
assert len(a["results"]) == len(b["results"]) == 2
for ra, rb in zip(a["results"], b["results"]):
    assert ra["label"] == rb["label"]
    if rb.get("status") == "device_disagrees":
        print("%s flagged device_disagrees on rusticl" % rb["label"])
        continue
    for zone in ("epicentre", "attenuation", "whole"):
        for k, x in ra[zone].items():
            y = rb[zone][k]
            if isinstance(x, float) and k.startswith("max"):
                assert "%.3e" % x == "%.3e" % y, (ra["label"], zone, k, x, y)
    assert rb["timing"]["timer"] in ("profiling events", "wall time: the driver's profiling events gave no time")
PY

TP=(throughput --models fq2,cq2 --reps 2 --min-time 0.002 --work-items 8 --variants default --no-host-c --no-sweep --quiet)
"$BIN" "${TP[@]}" --platform "$P" --out "$T/tp" 2>"$T/err" && ok || bad "throughput on rusticl: $(cat "$T/err")"
check_json "$T/tp/throughput.json" "throughput on rusticl: every row measured, the scalar kernels" <<'PY'
assert "llvmpipe" in d["context"]["device"]
assert all(r["status"] == "ok" for r in d["results"]), [r for r in d["results"] if r["status"] != "ok"]
assert len(d["results"]) == 3 * 2
assert "-DTP_W=1" in d["builds"][0]["build_options"], d["builds"]
PY

POCL_DEVICES="pthread basic" "$BIN" "${TP[@]}" --device all --out "$T/all" 2>"$T/err" && ok ||
    bad "--device all over three devices: $(cat "$T/err")"
check_json "$T/all/throughput.json" "--device all: three devices, each with its own context" <<'PY'
devs = d["context"]["devices"]
assert len(devs) == 3, devs
assert any("llvmpipe" in x["device"] for x in devs) and any("basic" in x["device"] for x in devs), devs
assert len({r["device"] for r in d["results"]}) == 3
PY
"$BIN" compare "$T/all" --out "$T/allc" --quiet 2>"$T/err" && ok || bad "compare of the three devices: $(cat "$T/err")"
check_json "$T/allc/compare.json" "compare lays the three drivers side by side" <<'PY'
assert len(d["runs"]) == 3, [r["name"] for r in d["runs"]]
PY
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
