# harden.sh - bad-input rows of issue 31 (sourced by tests/test_cli_errors.sh, in its folder):
# user code with pointers, a gate's "measured" outside its folder or not a regular file,
# MERL cells beyond float's range, outputs that name an input, "--" ending the options.

# High 1: every pointer construct refused at parse, with file:line:column or --model NAME:column
t 2 "^brdfbench accuracy: --model z:1:5: '\*' before a value reads through a pointer: pointers are not accepted in a model" accuracy --model 'z=c + *(float*)8' --out run
t 2 "^brdfbench accuracy: --model z:1: 'sizeof' is not accepted in a model" accuracy --model 'z=sizeof(c)==8 ? (((long*)&c)[2]=0x414141414141, c) : c' --out run
t 2 "^brdfbench accuracy: --model z:1:5: '&' takes an address \(or is a bitwise and\): pointers and bit operations are not accepted" accuracy --model 'z=c + &n' --out run
t 2 "^brdfbench accuracy: --model z:1:6: indexing a float \(a vector or an array is indexed\)" accuracy --model 'z=c + n[2]' --out run
t 2 "^brdfbench accuracy: --model z:5: 'memcpy' is called, which is neither an OpenCL C math built-in" accuracy --model 'z=c + memcpy(c, n, 8)' --out run
printf '{"gates":[{"model":"r","expression":"sizeof(c)==8 ? (((long*)&c)[2]=0x414141414141, c) : c","metric":"whole.max_abs","max":1}]}' >g31ptr.json
WHAT="g31ptr.json: the issue's gates-file expression"
t 2 "^brdfbench gate: g31ptr\.json:1:[0-9]+: gate 1: --model r:1: 'sizeof' is not accepted in a model" gate g31ptr.json
printf '/* brdfbench-model\n * name: ptr\n */\nREAL ptr(REAL c, REAL n)\n{\n    float *q = 0;\n    return c;\n}\n' >ptr.cl
t 2 "^brdfbench accuracy: ptr\.cl:6:11: '\*' after a type \(a pointer\) is not accepted" accuracy --model-file ptr.cl --out run
printf '/* brdfbench-model\n * name: inc\n */\n#include "/etc/passwd"\nREAL inc(REAL c, REAL n) { return c; }\n' >inc.cl
t 2 "^brdfbench accuracy: inc\.cl:4:1: directive '#include' is not accepted in a model" accuracy --model-file inc.cl --out run
printf '/* brdfbench-model\n * name: vol\n */\nREAL vol(REAL c, REAL n) { volatile REAL x = c; return x; }\n' >vol.cl
t 2 "^brdfbench accuracy: vol\.cl:4:28: 'volatile' is not accepted in a model" accuracy --model-file vol.cl --out run

# High 2: a gate's "measured" is confined to the gates file's folder and read as a regular file
mkdir -p g31m
printf '{"gates":[{"model":"fq2","metric":"measured.rms","measured":"/etc/passwd","max":1}]}' >g31m/out.json
t 2 "^brdfbench gate: g31m/out\.json:1:[0-9]+: gate 1: \"measured\" '/etc/passwd' lies outside the gates file's folder g31m; a gates file reads only the materials in its own folder" gate g31m/out.json
mkfifo g31m/fifo.binary
printf '{"gates":[{"model":"fq2","metric":"measured.rms","measured":"fifo.binary","max":1}]}' >g31m/fifo.json
t 2 "multi:^brdfbench gate: g31m/fifo\.binary: cannot open: is a FIFO, not a regular file" gate g31m/fifo.json --timeout 20
cp /etc/passwd g31m/pw.binary
printf '{"gates":[{"model":"fq2","metric":"measured.rms","measured":"pw.binary","max":1}]}' >g31m/pw.json
t 2 "multi:^brdfbench gate: g31m/pw\.binary: not a MERL file: it does not begin with three table dimensions" gate g31m/pw.json

# Medium 1: a MERL cell beyond float's range once scaled (1e300 in the red block's first cell)
python3 -c '
import array, sys
v = array.array("d", [0.5]) * (3 * 1458000)
v[0] = 1e300
with open("huge_cell.binary", "wb") as f:
    f.write(array.array("i", [90, 90, 180]).tobytes()); f.write(v.tobytes())'
WHAT="huge_cell.binary: a MERL file whose first red cell is 1e300"
t 2 "^brdfbench measured: huge_cell\.binary: the red block's cell 0 \(theta_h 0, theta_d 0, phi_d 0\) is 1e\+300, beyond float's range once scaled" measured huge_cell.binary --out run

# High 4: an output that names an input (the same file, a link to it, a file in an input folder)
printf '{"gates":[{"model":"fq2","metric":"whole.max_abs","n_max":10,"samples":64,"max":1}]}' >g31o.json
ln -sf g31o.json g31o_link.json
t 2 "^brdfbench gate: --json: 'g31o\.json' is 'g31o\.json', an input of this command \(the same file\): an output may not replace what the command reads" gate g31o.json --json g31o.json
t 2 "^brdfbench gate: --junit: 'g31o_link\.json' is 'g31o\.json', an input of this command" gate g31o.json --junit g31o_link.json
t 2 "^brdfbench measured: --json: 'huge_cell\.binary' is 'huge_cell\.binary', an input of this command" measured huge_cell.binary --json huge_cell.binary
t 2 "^brdfbench rows: --output: 'base/accuracy\.json' is 'base/accuracy\.json', an input of this command" rows base/accuracy.json --output base/accuracy.json
t 2 "^brdfbench compare: --json: 'base/accuracy\.json' is a file in 'base', an input folder of this command" compare base base --json base/accuracy.json
cp "$F/quad.cl" m31.cl
t 2 "^brdfbench accuracy: --json: 'm31\.cl' is 'm31\.cl', an input of this command" accuracy --model-file m31.cl --json m31.cl

# Low: "--" ends the options (a file named like a flag)
t 2 "^brdfbench rows: --weird: no such file or folder" rows -- --weird

# Medium 7: a kernel cache PoCL cannot write makes it report no device: exit 3 naming the cache, not 77 ("skipped")
t 3 "^brdfbench accuracy: PoCL's kernel cache /proc/pocl-cache cannot be written or made \(set by POCL_CACHE_DIR\)" POCL_CACHE_DIR=/proc/pocl-cache accuracy --models fq2 --n-max 5 --samples 16 --out run

# Medium 4: a hand-written rows document is checked as strictly as the file it stands for
"$BIN" rows base --format json --output rows31.json >/dev/null 2>&1
python3 -c '
import json
d = json.load(open("rows31.json"))
for m in d["rows"][0]["metrics"]:
    if m["name"] == "epicentre.max_rel":
        m["value"] = -1
json.dump(d, open("rows31_neg.json", "w"), indent=1)
d = json.load(open("rows31.json"))
d["rows"][0]["status"] = "failed"
d["rows"][0]["reason"] = "bad \u001b[31mred\u001b[0m"
json.dump(d, open("rows31_esc.json", "w"), indent=1)'
WHAT="rows31_neg.json: a rows document whose first row's epicentre.max_rel is -1"
t 2 "^brdfbench compare: rows31_neg\.json:[0-9]+:[0-9]+: \"value\" of epicentre\.max_rel is -1 \(accepted: a figure where lower is better is in \[0, 1e\+100\]" compare rows31.json rows31_neg.json --fail-if-less-accurate
WHAT="rows31_esc.json: a rows document whose first row's reason holds terminal escape sequences"
t 2 "^brdfbench compare: rows31_esc\.json:[0-9]+:[0-9]+: \"reason\" holds an escape character" compare rows31.json rows31_esc.json

# Medium 6: another command's results into a folder of `all` would be reported as all's run
t 3 "^brdfbench accuracy: --out: R0 is a run folder of .brdfbench all. \(it holds run\.json\)" accuracy --models fq2 --n-max 5 --samples 16 --out R0

# Low: a rows document whose label or keys do not fit is refused (cut at 255 bytes, two rows would read as one)
python3 -c '
import copy, json
d = json.load(open("rows31.json"))
rows = []
for i in range(2):
    r = copy.deepcopy(d["rows"][0])
    r["row"] = r["model"] = "m" * 300 + str(i)
    r["keys"] = {"model": r["row"]}
    rows.append(r)
d["rows"] = rows
json.dump(d, open("rows31_long.json", "w"))
d = json.load(open("rows31.json"))
d["rows"][0]["keys"] = {"k%d" % i: str(i) for i in range(10)}
json.dump(d, open("rows31_keys.json", "w"))'
WHAT="rows31_long.json: two rows whose labels differ only after byte 300"
t 2 "^brdfbench rows: rows31_long\.json:[0-9]+:[0-9]+: a row whose keys do not fit \(at most 8 keys, a label and each key of at most 255 bytes\)" rows rows31_long.json --output run31_rows.txt
WHAT="rows31_keys.json: a row with 10 keys"
t 2 "^brdfbench compare: rows31_keys\.json:[0-9]+:[0-9]+: a row whose keys do not fit" compare rows31.json rows31_keys.json
