#!/usr/bin/env bash
# test_device_csv.sh - --device all gathers the CSV as it gathers the JSON: OUT/accuracy.csv and
# OUT/throughput.csv hold a first column device (the device's name, CSV-quoted) and every
# device's rows of OUT/devices/<k>/, in turn; --csv FILE and --csv - deliver that file. Two
# devices: PoCL's pthread and basic (POCL_DEVICES="pthread basic").
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
cd "$T" || exit 1
export POCL_DEVICES="pthread basic"
NDEV=$("$BIN" list --json - 2>/dev/null | python3 -c 'import json,sys; d=json.load(sys.stdin); print(sum(len(p["devices"]) for p in d["platforms"]))')
if [ "${NDEV:-0}" -lt 2 ]; then
    echo "0 passed, 0 failed; SKIP: POCL_DEVICES=\"pthread basic\" gives ${NDEV:-no} OpenCL devices, not 2 or more"
    exit 77
fi
# device 0's name, as list names it (the tag of its rows; the second of --device 0,0 is "NAME #2")
NAME0=$("$BIN" list --json - | python3 -c 'import json,sys; d=json.load(sys.stdin); print([p for p in d["platforms"] if p["devices"]][0]["devices"][0]["name"])')

# 1. accuracy --out: OUT/accuracy.csv is the devices' files, each row led by its device's name
ACC=(accuracy --models fq2,cq2 --n-min 2 --n-max 5 --samples 16 --quiet)
"$BIN" "${ACC[@]}" --device all --out acc 2>err && ok || bad "accuracy --device all --out: $(tail -3 err)"
jsoncheck device_csv acc/accuracy.csv acc accuracy.csv "$NDEV" && ok || bad "accuracy.csv gathered from the devices"

# 2. throughput --out with --csv FILE: the same gathered file delivered there too
TP=(throughput --models fq2 --variants default --n-modes uniform --no-sweep --no-host-c --reps 1 --min-time 0.001 --quiet)
"$BIN" "${TP[@]}" --device all --out tp --csv tp.csv 2>err && ok || bad "throughput --device all --csv: $(tail -3 err)"
jsoncheck device_csv tp/throughput.csv tp throughput.csv "$NDEV" && ok || bad "throughput.csv gathered from the devices"
cmp -s tp.csv tp/throughput.csv && ok || bad "--csv tp.csv differs from the run's gathered throughput.csv"

# 3. --csv - without --out: the gathered CSV alone on standard output (accuracy is deterministic:
#    the file of 1.), no results/ folder, and the temporary folder of the devices' runs gone
mkdir -p tmp
TMPDIR=$T/tmp "$BIN" "${ACC[@]}" --device all --csv - >stdout.csv 2>err && ok || bad "accuracy --device all --csv -: $(tail -3 err)"
cmp -s stdout.csv acc/accuracy.csv && ok || bad "--csv - differs from the --out run's accuracy.csv: $(head -c 300 stdout.csv)"
[ ! -e results ] && [ -z "$(ls -A tmp)" ] && ok || bad "--csv - left results/ or its temporary folder: $(ls -A . tmp)"

# 4. the same device twice: its rows under NAME, then under "NAME #2"
"$BIN" "${ACC[@]}" --device 0,0 --csv twice.csv 2>err && ok || bad "accuracy --device 0,0 --csv: $(tail -3 err)"
jsoncheck csv_device_tags twice.csv "$NAME0" "$NAME0 #2" && ok || bad "--device 0,0: tags $NAME0 and $NAME0 #2"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
