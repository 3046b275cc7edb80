#!/usr/bin/env bash
# test_cli_errors.sh - the bad-input table: every command refuses bad input with one line
# that names the argument (or the file, line and column) and what it accepts, and the exit
# code of docs/architecture.md (2 bad input, 3 runtime/output error). Each row below asserts both.
#
# BAD_INPUTS_MD=FILE writes the table with each row's result as Markdown (docs/bad-inputs.md
# is made this way).
set -u
BIN=${BRDFBENCH:?BRDFBENCH must name the brdfbench binary}
SRC=${SRC_DIR:?}
F=$SRC/tests/test_usermodel_files
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
case "${BAD_INPUTS_MD:-}" in ""|/*) ;; *) BAD_INPUTS_MD=$PWD/$BAD_INPUTS_MD ;; esac
cd "$T" || exit 1
pass=0 fail=0 row=0
md=""

# t CODE REGEX [VAR=VALUE ...] ARGS...: runs brdfbench ARGS (with the environment variables
# given first); the exit code must be CODE and stderr must hold exactly one line matching
# REGEX, prefixed "brdfbench COMMAND: " (or "brdfbench: " for the dispatcher). Where REGEX
# starts with "multi:" more lines may follow (a compile error's build log, the usage text).
t() {
    local code=$1 pattern=$2
    shift 2
    local envs=()
    while [ $# -gt 0 ] && [[ "$1" =~ ^[A-Z_]+= ]]; do envs+=("$1"); shift; done
    row=$((row + 1))
    env "${envs[@]}" "$BIN" "$@" >"$T/out" 2>"$T/err"
    local rc=$? verdict=ok first
    local lines
    lines=$(wc -l <"$T/err")
    first=$(grep -m1 -E -- "${pattern#multi:}" "$T/err")
    if [ "$rc" -ne "$code" ]; then
        verdict="exit $rc, expected $code"
    elif [ -z "$first" ]; then
        verdict="no stderr line matches /${pattern#multi:}/"
    elif [[ "$pattern" != multi:* ]] && [ "$lines" -ne 1 ]; then
        verdict="$lines lines on stderr, expected 1"
    fi
    if [ "$verdict" = ok ]; then
        pass=$((pass + 1))
    else
        fail=$((fail + 1))
        echo "FAIL row $row: brdfbench $* -> $verdict: $(head -c 400 "$T/err")" >&2
    fi
    local shown="${envs[*]:+${envs[*]} }brdfbench $*"
    shown=${shown//$T\//}
    shown=${shown//$SRC\//}
    first=${first//$T\//}
    first=${first//$SRC\//}
    md+="| $row | \`${shown//|/\\|}\` | $rc | ${first//|/\\|} | $verdict |"$'\n'
}

# Fixtures: gates files with one fault each.
printf '{"gates":[{"model":"fq2","metric":"epicentre.max_rel","max":0.0126},]}' >trailing_comma.json
printf '{"gates":[\n  {"model":"fq2","metric":"epicentre.max_err","max":0.0126}\n]}\n' >bad_metric.json
printf '{"gates":[\n  {"model":"fq2","metric":"epicentre.max_rel"}\n]}\n' >no_bound.json
printf '{"gates":[{"model":"fq2","metric":"epicentre.max_rel","min":0.2,"max":0.1}]}' >min_above_max.json
printf '{"gates":[{"model":"fq2","metric":"epicentre.max_rel","n_min":0,"max":0.1}]}' >n_min_zero.json
printf '{"gates":[{"model":"fq2","metric":"epicentre.max_rel","mx":0.1}]}' >typo_key.json
printf '{"gates":[{"model":"fq2","metric":"epicentre.max_rel","max":"0.1"}]}' >string_bound.json
printf '{"gates":[{"model":"fq2","metric":"epicentre.max_rel","samples":100,"max":0.1}]}' >bad_samples.json
printf '{"gates":[{"model":"fq9","metric":"epicentre.max_rel","max":0.1}]}' >unknown_model.json
printf '{"gates":[{"model":"fq:Q=2","metric":"epicentre.max_rel","max":0.1}]}' >param_range.json
printf '{"gates":[]}' >no_gates.json
printf '[{"model":"fq2"}]' >array_root.json
: >empty.json
printf '{"gates":[{"model":"mine","model_file":"missing.cl","metric":"whole.max_abs","max":1}]}' >missing_model_file.json
printf '{"gates":[{"model":"e","expression":"c; return 0","metric":"whole.max_abs","max":1}]}' >bad_expression.json
printf '{"gates":[{"model":"fq2","metric":"whole.max_abs","n_min":1,"n_max":1000,"n_step":0.0001,"samples":16,"max":1}]}' >huge_grid.json
printf '{"gates":[{"model":"fq2","metric":"epicentre.max_rel","max":0.0126}]}' >good.json
printf '{"schema": "brdfbench.accuracy/1", "results": [' >truncated_baseline.json
printf '{"gates":[{"model":"cq2","metric":"albedo.max","max":1}]}' >albedo_cq2.json
printf '{"gates":[{"model":"phongn","metric":"albedo.max","n_step":0.1,"max":1}]}' >albedo_many.json
mkdir -p folder

# The dispatcher.
t 2 "^brdfbench: unknown command 'frobnicate' \(accepted: list accuracy " frobnicate
t 2 'multi:^usage: brdfbench COMMAND'
t 2 "^brdfbench: unknown command '--bogus'" --bogus
# list
t 2 "^brdfbench list: unknown option '--bogus' \(see brdfbench list --help\)" list --bogus
# accuracy: numbers
t 2 "^brdfbench accuracy: --n-min: 'abc' is not a finite number in \[" accuracy --n-min abc
t 2 "^brdfbench accuracy: --n-min: 'nan' is not a finite number" accuracy --n-min nan
t 2 "^brdfbench accuracy: --n-max: 'inf' is not a finite number" accuracy --n-max inf
t 2 "^brdfbench accuracy: --n-min: '1e999' is not a finite number" accuracy --n-min 1e999
t 2 "^brdfbench accuracy: --n-min: '-5' is not a finite number in \[0.1, 1e\+06\]" accuracy --n-min -5
t 2 "^brdfbench accuracy: --n-max: '0' is not a finite number" accuracy --n-max 0
t 2 "^brdfbench accuracy: --n-min: '2x' is not a finite number" accuracy --n-min 2x
t 2 "^brdfbench accuracy: --n-min: '' is not a finite number" accuracy --n-min=
t 2 "^brdfbench accuracy: --n-min \(50\) must be below --n-max \(10\)" accuracy --n-min 50 --n-max 10
t 2 "^brdfbench accuracy: --n-step: '0' is not a finite number" accuracy --n-step 0
t 2 "^brdfbench accuracy: --n-step: 1e-09 gives [0-9]+ values of n \(accepted: 2 to 10000000\)" accuracy --n-step 1e-9
t 2 "^brdfbench accuracy: --samples: 100 is not a multiple of 16" accuracy --samples 100
t 2 "^brdfbench accuracy: --samples: '0' is not an integer in \[16, " accuracy --samples 0
t 2 "^brdfbench accuracy: --samples: '12x' is not an integer" accuracy --samples 12x
t 2 "^brdfbench accuracy: --samples: '99999999999999999999' is not an integer" accuracy --samples 99999999999999999999
t 2 "^brdfbench accuracy: --n-min: missing value" accuracy --n-min
# accuracy: models and parameters
t 2 "^brdfbench accuracy: unknown model 'nosuch' \(accepted: phong, blinn, " accuracy --models nosuch
t 2 "^brdfbench accuracy: model 'fq': parameter Q='1.5' must be a number in \[1e-06, 0.999999\]" accuracy --models fq:Q=1.5
t 2 "^brdfbench accuracy: model 'fq': parameter Q='nan' must be a number" accuracy --models fq:Q=nan
t 2 "^brdfbench accuracy: model 'lyon': parameter k='2.5' must be an integer in \[1, 16\]" accuracy --models lyon:k=2.5
t 2 "^brdfbench accuracy: model 'cq2' takes no parameters \(got 'k'\)" accuracy --models cq2:k=2
t 2 "^brdfbench accuracy: --models: empty entry in list 'cq2,,fq2'" accuracy --models cq2,,fq2
t 2 "^brdfbench accuracy: unknown option '--frobnicate' \(see brdfbench accuracy --help\)" accuracy --frobnicate
# accuracy: device selection and limits
t 2 "^brdfbench accuracy: --platform: '99' is not an integer in \[0, 63\]" accuracy --platform 99
t 2 "^brdfbench accuracy: --device: '-1' is not an integer in \[0, 63\]" accuracy --device -1
t 2 "^brdfbench accuracy: --platform: 9 is out of range \(accepted: 0 to " accuracy --platform 9 --n-max 4 --samples 16
t 2 "^brdfbench accuracy: --kernel-dir: /nonexistent does not hold brdf_models.h" accuracy --kernel-dir /nonexistent
# POCL_MEMORY_LIMIT=1 caps PoCL's device at 1 GiB (256 MiB per buffer): 9990001 values of n need
# 9990001 x 32 bytes = 3.2e8, more than one buffer may hold.
t 2 "^brdfbench accuracy: --n-step: 9990001 values of n need 3.2e\+08 bytes, more than the device allows" \
    POCL_MEMORY_LIMIT=1 accuracy --n-min 1 --n-max 1000 --n-step 0.0001 --samples 16
# accuracy: output folders
t 3 "^brdfbench accuracy: --out: /dev/full is not a folder" accuracy --n-max 4 --samples 16 --out /dev/full
t 3 "^brdfbench accuracy: --out: cannot create folder /proc/brdf: " accuracy --n-max 4 --samples 16 --out /proc/brdf
t 3 "^brdfbench accuracy: --out: cannot create folder good.json/run: Not a directory" accuracy --n-max 4 --samples 16 --out good.json/run
# user models: files and expressions (accepted by every command that evaluates models)
t 2 "^brdfbench accuracy: --model-file: cannot read /nonexistent.cl: No such file" accuracy --model-file /nonexistent.cl
t 2 "^brdfbench accuracy: --model-file: cannot read folder: Is a directory" accuracy --model-file folder
t 2 "^brdfbench accuracy: .*no_header.cl:1: a model file begins with a header comment" accuracy --model-file "$F/no_header.cl"
t 2 "^brdfbench accuracy: .*bad_param.cl:3: parameter 'k': MIN 5 must be below MAX 1" accuracy --model-file "$F/bad_param.cl"
t 2 "^brdfbench accuracy: .*unknown_key.cl:3: unknown key 'colour' \(accepted: name, param, " accuracy --model-file "$F/unknown_key.cl"
t 2 "^brdfbench accuracy: .*no_function.cl: no function 'nofunction' after the header" accuracy --model-file "$F/no_function.cl"
t 2 "^brdfbench accuracy: --model scaled: user model 'scaled' is already defined by .*scaled.cl" accuracy --model-file "$F/scaled.cl" --model 'scaled=c'
t 2 "^brdfbench accuracy: model 'scaled': parameter k='20' must be a number in \[0, 10\]" accuracy --model-file "$F/scaled.cl" --models scaled:k=20
t 2 "multi:bad_syntax.cl:6:[0-9]+: .*expected ';'" accuracy --model-file "$F/bad_syntax.cl" --n-max 4 --samples 16 --out run
t 2 "^brdfbench accuracy: --model: 'sq' is not NAME=EXPR" accuracy --model sq
t 2 "^brdfbench accuracy: --model: name '1abc' is not an identifier" accuracy --model '1abc=c'
t 2 "^brdfbench accuracy: --model fq2: 'fq2' is the name of a built-in model" accuracy --model 'fq2=c*c'
t 2 "^brdfbench accuracy: --model a:1:1: this expression is computed and then dropped" accuracy --model 'a=c; return 0'
t 2 "^brdfbench accuracy: --model a: the expression must have 1 to 1000 characters" accuracy --model 'a='
t 2 "multi:--model e1:1:13: .*undeclared identifier 'q'" accuracy --model 'e1=pow(c, n) * q' --n-max 4 --samples 16 --out run
t 2 "^brdfbench render: --model: 'x' is not NAME=EXPR" render --model x
t 2 "^brdfbench throughput: .*no_header.cl:1: a model file begins with a header comment" throughput --model-file "$F/no_header.cl"
t 2 "^brdfbench all: --model fq2: 'fq2' is the name of a built-in model" all --model 'fq2=c'
t 2 "^brdfbench gate: --model-file: cannot read /nonexistent.cl: No such file" gate good.json --model-file /nonexistent.cl
# gate: the command line
t 2 "^brdfbench gate: a gates file is missing" gate
t 2 "^brdfbench gate: one gates file expected, got 'good.json' and 'other.json'" gate good.json other.json
t 2 "^brdfbench gate: /nonexistent.json: cannot read the gates file: No such file" gate /nonexistent.json
t 2 "^brdfbench gate: folder: is a folder, not a gates file" gate folder
t 2 "^brdfbench gate: --tolerance: '2' is not a finite number in \[0, 1\]" gate good.json --baseline good.json --tolerance 2
t 2 "^brdfbench gate: --tolerance: only with --baseline" gate good.json --tolerance 0.01
t 2 "^brdfbench gate: --baseline: cannot read /nonexistent: No such file" gate good.json --baseline /nonexistent
t 2 "^brdfbench gate: --baseline: truncated_baseline.json:1:[0-9]+: unexpected end of file" gate good.json --baseline truncated_baseline.json
t 2 "^brdfbench gate: --baseline: good.json:1:1: not an accuracy.json" gate good.json --baseline good.json
t 3 "^brdfbench gate: --junit: folder /nonexistent/dir does not exist" gate good.json --junit /nonexistent/dir/x.xml
t 3 "^brdfbench gate: --json: folder is a folder \(a file name is expected\)" gate good.json --json folder
t 2 "^brdfbench gate: unknown option '--junit-file' \(see brdfbench gate --help\)" gate good.json --junit-file x
# gate: the gates file (file:line:column: problem)
t 2 "^brdfbench gate: trailing_comma.json:1:[0-9]+: trailing comma" gate trailing_comma.json
t 2 "^brdfbench gate: bad_metric.json:2:27: gate 1: unknown metric 'epicentre.max_err' \(accepted: epicentre.max_rel, " gate bad_metric.json
t 2 "^brdfbench gate: no_bound.json:2:3: gate 1: a bound is missing" gate no_bound.json
t 2 "^brdfbench gate: min_above_max.json:1:[0-9]+: gate 1: \"min\" \(0.2\) is above \"max\" \(0.1\)" gate min_above_max.json
t 2 "^brdfbench gate: n_min_zero.json:1:[0-9]+: gate 1: \"n_min\" 0 is out of range" gate n_min_zero.json
t 2 "^brdfbench gate: typo_key.json:1:[0-9]+: gate 1: unknown member \"mx\" \(accepted: model, " gate typo_key.json
t 2 "^brdfbench gate: string_bound.json:1:[0-9]+: gate 1: \"max\" is a string, a number expected" gate string_bound.json
t 2 "^brdfbench gate: bad_samples.json:1:[0-9]+: gate 1: \"samples\" 100 is out of range \(accepted: a multiple of 16" gate bad_samples.json
t 2 "^brdfbench gate: unknown_model.json:1:[0-9]+: gate 1: unknown model 'fq9'" gate unknown_model.json
t 2 "^brdfbench gate: param_range.json:1:[0-9]+: gate 1: model 'fq': parameter Q='2' must be a number" gate param_range.json
t 2 "^brdfbench gate: no_gates.json:1:[0-9]+: \"gates\" has 0 gates \(accepted: 1 to 1000\)" gate no_gates.json
t 2 "^brdfbench gate: array_root.json:1:1: the gates file is an object" gate array_root.json
t 2 "^brdfbench gate: empty.json: empty file" gate empty.json
t 2 "^brdfbench gate: missing_model_file.json:1:[0-9]+: gate 1: --model-file: cannot read ./missing.cl" gate missing_model_file.json
t 2 "^brdfbench gate: bad_expression.json:1:[0-9]+: gate 1: --model e:1:1: this expression is computed and then dropped" gate bad_expression.json
t 2 "^brdfbench gate: huge_grid.json:1:11: gate 1: grid: --n-step: 9990001 values of n need 3.2e\+08 bytes, more than the device allows" \
    POCL_MEMORY_LIMIT=1 gate huge_grid.json
t 2 "^brdfbench gate: albedo_cq2.json:1:[0-9]+: gate 1: albedo.max needs a normalised or microfacet model \(cq2 is quadratic\)" gate albedo_cq2.json
t 2 "^brdfbench gate: albedo_many.json:1:1[0-9]: gate 1: albedo.max over 9981 values of n \(accepted: at most 1000" gate albedo_many.json
# all, plot, heatmap, render, fit, reproduce
t 2 "^brdfbench all: unknown option '--bogus' \(see brdfbench all --help\)" all --bogus
t 2 "^brdfbench all: unknown model 'nosuch'" all --models nosuch
t 2 "^brdfbench plot: RUN_DIR '/nonexistent' is not a folder" plot /nonexistent
t 2 "^brdfbench plot: unexpected argument 'b'" plot folder b
t 2 "^brdfbench heatmap: --label: missing value" heatmap --label
t 2 "^brdfbench render: --size: '0x10' is not WxH with W and H integers in \[16, 16384\]" render --size 0x10
t 2 "^brdfbench render: --size: 4096x4096 is outside the accepted range: .*device" POCL_MEMORY_LIMIT=1 render --size 4096x4096
t 2 "^brdfbench render: --scene: 'moon' is not a list of spheres, teapot, bunny" render --scene moon
t 2 "^brdfbench render: --exposure: 'nan' is not a finite number in \[0.01, 100\]" render --exposure nan
t 2 "^brdfbench render: --light: 'laser' is not directional or point" render --light laser
t 2 "^brdfbench render: --reps: '0' is not an integer in \[1, 1000\]" render --reps 0
t 2 "^brdfbench fit: --n-min: 'x' is not a finite number" fit --n-min x
t 2 "^brdfbench fit: --max-abs: '-1' is not a finite number in \[1e-06, 1\]" fit --max-abs -1
t 2 "^brdfbench fit: --max-abs: '1e-300' is not a finite number in \[1e-06, 1\]" fit --max-abs 1e-300
t 2 "^brdfbench fit: --max-rel: '0' is not a finite number in \[1e-06, 1\]" fit --objective max_abs --max-rel 0
t 2 "^brdfbench fit: --power: '17' is not an integer in \[1, 16\]" fit --power 17
t 2 "^brdfbench fit: --objective: 'bogus' is not an objective \(accepted: max_rel, max_abs\)" fit --objective bogus
t 2 "^brdfbench fit: --max-rel caps the figure --objective max_rel minimises" fit --family gauss --max-rel 0.01
t 2 "^brdfbench frontier: --samples: 17 is not a multiple of 16" frontier --samples 17
t 2 "^brdfbench frontier: unknown option '--bogus' \(see brdfbench frontier --help\)" frontier --bogus
t 2 "^brdfbench fit: --samples: '7' is not an integer in \[16, " fit --samples 7
t 2 "^brdfbench fit: unknown option '--bogus' \(see brdfbench fit --help\)" fit --bogus
t 2 "^brdfbench reproduce: --samples: '0' is not an integer in \[16, " reproduce --samples 0
t 2 "^brdfbench reproduce: --q-step: 'nan' is not a finite number in \[0.0001, 0.5\]" reproduce --q-step nan
t 2 "^brdfbench reproduce: unknown option '--bogus' \(see brdfbench reproduce --help\)" reproduce --bogus
t 2 "^brdfbench throughput: unknown option '--bogus' \(see brdfbench throughput --help\)" throughput --bogus
t 2 "^brdfbench throughput: --min-time: '0' is not a finite number in \[0.0001, 10\]" throughput --min-time 0
t 2 "^brdfbench throughput: --work-items: '-1' is not an integer in \[1, 65536\]" throughput --work-items -1
t 2 "^brdfbench throughput: --uniform-n: 'nan' is not a finite number" throughput --uniform-n nan
t 2 "^brdfbench throughput: --n-min \(5\) must be below --n-max \(2\)" throughput --n-min 5 --n-max 2
t 2 "^brdfbench throughput: --variants: unknown 'turbo' \(accepted: default, " throughput --variants turbo
t 2 "^brdfbench throughput: --sweep-samples: 100 is not a multiple of 16" throughput --sweep-samples 100
t 2 "^brdfbench compare: expected BASELINE RUN \[RUN \.\.\.\]" compare
t 2 "^brdfbench compare: unknown option '--bogus' \(see brdfbench compare --help\)" compare --bogus
t 2 "^brdfbench compare: --alpha: '2' is not a finite number in \[1e-06, 0.5\]" compare a b --alpha 2
t 2 "^brdfbench compare: --fail-if-slower: '-1' is not a finite number in \[0, 100\]" compare a b --fail-if-slower -1
t 2 "^brdfbench compare: nothere: No such file or directory" compare nothere nothere --out run
# measured (MERL files; the cases that need a whole 35 MB file are in test_measured_cli.sh)
: >empty.binary
printf '\x5a\x00\x00\x00\x5a\x00\x00\x00\x68\x01\x00\x00' >dims360.binary
printf '\x5a\x00\x00\x00\x5a\x00\x00\x00\xb4\x00\x00\x00' >headonly.binary
t 2 "^brdfbench measured: expected a MERL \.binary file or a folder of them" measured
t 2 "^brdfbench measured: nothere\.binary: No such file or directory \(expected a MERL \.binary file or a folder of them\)" measured nothere.binary
t 2 "^brdfbench measured: folder: no \.binary files in the folder" measured folder
t 2 "^brdfbench measured: --fit-cells: '10' is not an integer in \[100, 1458000\]" measured empty.binary --fit-cells 10
t 2 "^brdfbench measured: empty\.binary: short file: 0 bytes, a MERL file starts with three 32-bit dimensions" measured empty.binary --out run
t 2 "^brdfbench measured: dims360\.binary: dimensions 90 90 360 \(expected 90 90 180, product 1458000\)" measured dims360.binary --out run
t 2 "^brdfbench measured: headonly\.binary: size 12 bytes, 34992000 short of the 34992012 that dimensions 90 90 180 need" measured headonly.binary --out run
t 2 "^brdfbench all: --measured: nothere: No such file or directory" all --quick --measured nothere --out run
t 2 "^brdfbench fit: --device: 'all': all and lists are taken by throughput, accuracy and render" fit --device all

# accuracy and gate: the n range (float n; below 0.1 no float grid resolves the lobe) and the
# device-vs-double key of a gate
t 2 "^brdfbench accuracy: --n-min: '1e-300' is not a finite number in \[0.1, 1e\+06\]" accuracy --n-min 1e-300
t 2 "^brdfbench accuracy: --n-max: '0.09' is not a finite number in \[0.1, 1e\+06\]" accuracy --n-min 0.1 --n-max 0.09
printf '{"gates":[{"model":"fq2","metric":"epicentre.max_rel","n_min":1e-300,"max":0.1}]}' >n_min_tiny.json
t 2 "^brdfbench gate: n_min_tiny.json:1:[0-9]+: gate 1: \"n_min\" 1e-300 is out of range \(accepted: 0.1 <= n_min <= 1e\+06\)" gate n_min_tiny.json
printf '{"gates":[{"model":"fq2","metric":"epicentre.max_rel","max":0.1,"accept_device_disagreement":"yes"}]}' >accept_string.json
t 2 "^brdfbench gate: accept_string.json:1:[0-9]+: gate 1: \"accept_device_disagreement\" is a string, a boolean expected" gate accept_string.json
# One meaning per flag: a flag another command uses otherwise is refused with the right name.
t 2 "^brdfbench heatmap: --model: not a flag of brdfbench heatmap: .*--label LABEL" heatmap --model fvol
t 2 "^brdfbench render: --n: not a flag of brdfbench render: .*--mesh-n X" render --n 64
t 2 "^brdfbench render: --samples: not a flag of brdfbench render: .*--check-pixels N" render --samples 100
t 2 "^brdfbench throughput: --n: not a flag of brdfbench throughput: .*--uniform-n X" throughput --n 100
t 2 "^brdfbench throughput: --n-range: not a flag of brdfbench throughput: .*--n-min LO --n-max HI" throughput --n-range 2:1000
t 2 "^brdfbench all: --n-min \(50\) must be below --n-max \(10\)" all --n-min 50 --n-max 10
t 2 "^brdfbench all: --samples: 100 is not a multiple of 16" all --samples 100
t 2 "^brdfbench accuracy: --quiet: takes no value \(got '--quiet=1'\)" accuracy --quiet=1
# Model lists: a parameter given twice is refused; NAME with two expressions is refused.
t 2 "^brdfbench accuracy: model 'fq': parameter Q given twice \(at 'Q=0.6'" accuracy --models fq:Q=0.5,Q=0.6
t 2 "^brdfbench accuracy: model 'quad': parameter a given twice" accuracy --models quad:a=0.4,b=0.2,a=0.5
t 2 "^brdfbench accuracy: --model z: user model 'z' is already defined by --model z" accuracy --model 'z=c' --model 'z=c*c'
# Conventional output: one document on standard output, --json needs its value.
t 2 "^brdfbench accuracy: --json - and --csv -: one document at a time on standard output" accuracy --json - --csv -
t 2 "^brdfbench gate: --junit - and --json -: one document at a time on standard output" gate good.json --junit - --json -
t 2 "^brdfbench throughput: --json - and --csv -: one document at a time on standard output" throughput --json - --csv -
t 2 "^brdfbench list: --json: missing value \(expected --json FILE\|-\)" list --json
t 2 "^brdfbench version: unexpected argument 'now'" version now
# heatmap names the labels a run has when asked for one it does not have.
mkdir -p run1 && printf '{"model": "fq:Q=0.64"}' >run1/field_fq_Q_0.64.json && printf '{"model": "fvol"}' >run1/field_fvol.json
t 2 "^brdfbench heatmap: --label cq2: run1 has no model of that label \(accepted: fq:Q=0.64, fvol\)" heatmap run1 --label cq2

# Output paths, folders and input formats: a refused run makes no folder (the check below
# covers `run`), two reports never share a file, and a file of the wrong format is named as such.
printf 'bunny\\\001\002\000\003' >some.bin   # binary: a backslash, control bytes, a NUL
printf 'ply\nformat ascii 1.0\nend_header\n' >mesh.ply
t 2 "^brdfbench accuracy: --out: empty path \(accepted: a folder or file name\)" accuracy --out ''
t 2 "^brdfbench render: /dev/null:1: no bicubic_patch found \(expected a POV-Ray file with bicubic_patch blocks" \
    render --scene teapot --teapot-file /dev/null --out run
t 2 "^brdfbench render: some.bin:1: not a Wavefront OBJ file \(expected text lines of v, vt, vn and f statements\); found binary data" \
    render --scene bunny --bunny-file some.bin --out run
t 2 "^brdfbench render: mesh.ply:1: not a Wavefront OBJ file \(expected text lines of v, vt, vn and f statements\); found 'ply'" \
    render --scene bunny --bunny-file mesh.ply --out run
# every scene file is checked before any scene is shaded: with all three scenes and a launch
# deadline far too short for a shading pass, the bad bunny file is named (exit 2), not a
# deadline passed while shading the spheres (exit 3)
t 2 "^brdfbench render: some.bin:1: not a Wavefront OBJ file" render --bunny-file some.bin --timeout 0.01 --out run
t 2 "multi:bad_syntax.cl:6:[0-9]+: error: expected ';'" all --quick --model-file "$F/bad_syntax.cl" --out run
t 2 "^brdfbench gate: --json: 'same.json' is the file --junit names \('./same.json'\)" gate good.json --junit ./same.json --json same.json
ln -s same.json link.json
t 2 "^brdfbench gate: --json: 'link.json' is the file --junit names \('same.json'\)" gate good.json --junit same.json --json link.json
t 2 "^brdfbench gate: --json: '-' is the file --junit names \('/dev/fd/1'\)" gate good.json --junit /dev/fd/1 --json -
t 2 "^brdfbench accuracy: --timeout: 'inf' is not a finite number in \[0.01, 604800\]" accuracy --timeout inf
# A compile error's first line is the compiler's own FILE:LINE:COL line.
"$BIN" accuracy --model-file "$F/bad_syntax.cl" --n-max 4 --samples 16 --out run >/dev/null 2>"$T/err"
head -n 1 "$T/err" | grep -qE "^[^ ]*bad_syntax.cl:6:[0-9]+: error: expected ';'" && pass=$((pass + 1)) ||
    { fail=$((fail + 1)); echo "FAIL: a compile error starts with: $(head -n 1 "$T/err")" >&2; }

# One more check: no refused run above wrote its output folder.
[ ! -e "$T/run" ] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL: a refused run wrote $T/run" >&2; }

if [ -n "${BAD_INPUTS_MD:-}" ]; then
    {
        echo "# Bad inputs"
        echo
        echo "Every row is a case of tests/test_cli_errors.sh: the command, the exit code it gave and the first"
        echo "matching line of stderr (each asserted: exit code and message). Exit 2 is bad input, 3 a runtime"
        echo "or output error (docs/architecture.md). Made with \`BAD_INPUTS_MD=docs/bad-inputs.md bash tests/test_cli_errors.sh\`"
        echo "(BRDFBENCH and SRC_DIR set as ctest sets them): $row cases, one check that no refused run"
        echo "wrote an output folder and one that a compile error's first line is FILE:LINE:COL; $pass passed, $fail failed."
        echo
        echo "| # | command | exit | message | result |"
        echo "|---|---|---|---|---|"
        printf '%s' "$md"
    } >"$BAD_INPUTS_MD.tmp" && mv "$BAD_INPUTS_MD.tmp" "$BAD_INPUTS_MD"
fi
echo "$row cases + 2 checks: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
