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
WHAT=""   # what the next row's fixture holds, shown beside its command in docs/bad-inputs.md

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
    # (no env process for the rows that set no variable: most of them)
    if [ ${#envs[@]} -gt 0 ]; then
        env "${envs[@]}" "$BIN" "$@" >"$T/out" 2>"$T/err"
    else
        "$BIN" "$@" >"$T/out" 2>"$T/err"
    fi
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
    # the rest makes the row of docs/bad-inputs.md: only when it is written
    if [ -z "${BAD_INPUTS_MD:-}" ]; then
        WHAT=""
        return
    fi
    # a small text file the test made, named by the command, is shown with what it holds
    local a held=""
    for a in "$@"; do
        if [[ "$a" != /* && "$a" != -* ]] && [ -f "$a" ] && [ ! -L "$a" ] && [ "$(stat -c %s "$a")" -le 240 ] &&
            ! LC_ALL=C grep -qa '[^[:print:][:space:]]' "$a"; then
            held+="${held:+; }$a: $(tr '\n' ' ' <"$a" | sed 's/ *$//')"
        fi
    done
    [ -n "$WHAT" ] && held="$WHAT${held:+; $held}"
    local shown="${envs[*]:+${envs[*]} }brdfbench $*${held:+   [$held]}"
    WHAT=""
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
t 2 "^brdfbench accuracy: --shared-scale scales the heatmaps of --pictures \(accepted: with --pictures\)" accuracy --shared-scale --out "$T/ss"
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
t 2 "^brdfbench gate: --baseline: good.json:1:1: member \"schema\" is missing" gate good.json --baseline good.json
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
t 2 "^brdfbench throughput: --measured: nothere\.binary: No such file or directory \(expected a MERL \.binary file or a folder of them\)" throughput --measured nothere.binary --out run
t 2 "^brdfbench throughput: --measured: empty\.binary: short file: 0 bytes" throughput --measured empty.binary --out run
t 2 "^brdfbench render: --measured: folder: no \.binary files in the folder" render --measured folder --out run
t 2 "^brdfbench render: --measured: dims360\.binary: dimensions 90 90 360 \(expected 90 90 180, product 1458000\)" render --measured dims360.binary --out run
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
: >empty.pov
t 2 "^brdfbench render: empty.pov:1: no bicubic_patch found \(expected a POV-Ray file with bicubic_patch blocks" \
    render --scene teapot --teapot-file empty.pov --out run
t 2 "^brdfbench render: /dev/null: cannot read: is a character device, not a regular file" \
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

# ---- issue 23: the next hostile inputs -------------------------------------------------------
# Result files fed back (plot, heatmap, compare, gate --baseline), names that become file names,
# model texts, limits and environments. A real run folder R0 (all --quick) and an accuracy run
# are the fixtures; each row edits a copy. tests/test_hostile.sh checks the same inputs'
# effects (no file replaced outside the run folder, the earlier run kept, no hang).
# Both are made once by tests/fixture_runs.sh (`all --quick --models fq2 --out R0 --quiet` and
# `accuracy --models fq2,cq2 --n-max 50 --samples 256 --out base --quiet`; under ctest the
# fixture brdf_runs, in $BRDF_RUNS) and copied here; run by hand, the script makes them here.
if [ -n "${BRDF_RUNS:-}" ] && [ -f "$BRDF_RUNS/done" ]; then
    cp -r "$BRDF_RUNS/R0" "$BRDF_RUNS/base" .
else
    bash "$SRC/tests/fixture_runs.sh" "$T" >/dev/null 2>&1
fi
# ej DIR FILE PYTHON: a copy of R0 as DIR with PYTHON run on its JSON file FILE (as d; for
# plots.json, figure 0 also as f); pj, fj and rj name plots.json, field_fq2.json and run.json
ej() {
    WHAT="$1/$2: $3"
    rm -rf "$1" && cp -r R0 "$1"
    python3 - "$1/$2" "$3" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
f = d["figures"][0] if "figures" in d else None
exec(sys.argv[2])
json.dump(d, open(sys.argv[1], "w"))
PY
}
pj() { ej "$1" plots.json "$2"; }
fj() { ej "$1" field_fq2.json "$2"; }
rj() { ej "$1" run.json "$2"; }
# ff DIR FILE: a copy of R0 as DIR with its FILE replaced by a FIFO
ff() {
    rm -rf "$1" && cp -r R0 "$1" && rm "$1/$2" && mkfifo "$1/$2"
    WHAT="$1/$2: a FIFO"
}
# plots.json: a figure's file is a plain NAME.png, never a data file of the run or a path
for name in accuracy.json plots.json report.md field_fq2.json x.PNG.json ../escape.png /tmp/abs.png .hidden.png \
            'a b.png' '' 'x.png/' 'new
line.png' '-.png~' 'x.png.tmp.123'; do
    pj P "f['file'] = $(printf '%s' "$name" | python3 -c 'import json,sys; print(json.dumps(sys.stdin.read()))')"
    t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: \"file\" is \".*\" \(accepted: NAME.png, a plain file name" plot P
done
pj P "f['file'] = 'x' * 300 + '.png'"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: \"file\" is longer than 127 bytes" plot P
pj P "d['figures'][1]['file'] = f['file']"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: figure 2 has the file name \"curves_n16_paper1_fig2.png\" of figure 1" plot P
# plots.json: ranges a picture cannot show, and malformed figures
pj P "f['y_range'] = [1e-300, 2e-300]"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: \"y_range\" \[1e-300, 2e-300\] cannot be drawn" plot P
pj P "f['y_range'] = [1, 1 + 1e-15]"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: \"y_range\" \[1, 1.000000000000001\] cannot be drawn" plot P
pj P "f['y_range'] = [1e-320, 1e-310]"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: \"y_range\" \[9.99988867182683e-321, 9.999999999999969e-311\] cannot be drawn" plot P
pj P "f['x_range'] = [-1e301, 1e301]"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: \"x_range\" \[-1e\+301, 1e\+301\] cannot be drawn" plot P
pj P "f['y_log'] = True; f['y_range'] = [-1, 1]"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: \"y_range\" \[-1, 1\] cannot be drawn .*log axis" plot P
pj P "f['y_range'] = [0, 1, 2]"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: \"y_range\" must hold two numbers" plot P
pj P "f['y_range'] = 'auto'"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: member \"y_range\" is a string" plot P
pj P "f['kind'] = 'pie'"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: \"kind\" is \"pie\" \(accepted: lines, bars\)" plot P
pj P "f['y_format'] = 'hex'"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: \"y_format\" is \"hex\" \(accepted: plain, percent\)" plot P
pj P "f['series'][0]['colour'] = 12"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: \"colour\" must be an integer in \[-1, 9\]" plot P
pj P "f['series'][0]['x'] = f['series'][0]['x'][:-1]"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: series \".*\" has [0-9]+ x and [0-9]+ y values" plot P
pj P "f['series'] = f['series'] * 10"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: more than 24 series" plot P
pj P "f['vlines'] = [{'x': 1, 'label': 'v'}] * 5"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: more than 4 vlines" plot P
pj P "d['schema'] = 'brdfbench.plots/2'"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: schema \"brdfbench.plots/2\", expected \"brdfbench.plots/1\"" plot P
pj P "d['figures'] = {}"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: member \"figures\" is an object" plot P
pj P "del f['series']"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: member \"series\" is missing" plot P
pj P "f['title'] = 7"
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: member \"title\" is a number" plot P
# plots.json itself: not JSON, not a file
rm -rf P && cp -r R0 P
printf '{"schema": NaN}' >P/plots.json
WHAT='P/plots.json: {"schema": NaN}'
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: " plot P
printf '\xef\xbb\xbf{}' >P/plots.json
WHAT='P/plots.json: a UTF-8 byte order mark, then {}'
t 2 "^brdfbench plot: P/plots.json:1:1: " plot P
python3 -c 'print("[" * 100 + "]" * 100)' >P/plots.json
WHAT='P/plots.json: 100 nested arrays'
t 2 "^brdfbench plot: P/plots.json:.*(nest|deep)" plot P
printf '{"schema": "brdfbench.plots/1", "schema": "x", "figures": []}' >P/plots.json
WHAT='P/plots.json: "schema" twice'
t 2 "^brdfbench plot: P/plots.json:1:[0-9]+: .*duplicate" plot P
: >P/plots.json
WHAT='P/plots.json: empty'
t 2 "^brdfbench plot: P/plots.json: empty file" plot P
rm P/plots.json && mkfifo P/plots.json
WHAT='P/plots.json: a FIFO'
t 2 "^brdfbench plot: P/plots.json: is a FIFO, not a regular file" plot P
rm P/plots.json && ln -s /dev/zero P/plots.json
WHAT='P/plots.json -> /dev/zero'
t 2 "^brdfbench plot: P/plots.json: is a character device, not a regular file" plot P
rm P/plots.json && mkdir P/plots.json
WHAT='P/plots.json: a folder'
t 2 "^brdfbench plot: P/plots.json: is a folder, not a file" plot P
rm -rf P/plots.json && ln -s nowhere.json P/plots.json
WHAT='P/plots.json: a dangling link'
t 2 "^brdfbench plot: P/plots.json: cannot open: No such file or directory" plot P
# report: run.json and the pages fed back (report.md is rebuilt from them)
t 2 "^brdfbench report: RUN_DIR '/nonexistent' is not a folder" report /nonexistent
t 2 "^brdfbench report: unexpected argument 'b'" report R0 b
t 2 "^brdfbench report: base/run.json: No such file: not a run folder of .brdfbench all." report base
t 2 "^brdfbench report: --output: 'R0/accuracy.json' is inside RUN_DIR 'R0' \(accepted: RUN_DIR/report.md, a file outside the run folder, or -\)" \
    report R0 --output R0/accuracy.json
rj Q "d['schema'] = 'brdfbench.run/2'"
t 2 "^brdfbench report: Q/run.json:1:1: schema \"brdfbench.run/2\" is not brdfbench.run/1" report Q
rj Q "del d['command']"
t 2 "^brdfbench report: Q/run.json:1:1: member \"command\" is missing" report Q
rj Q "d['pictures'][0]['file'] = '../outside.png'"
t 2 "^brdfbench report: Q/run.json:1:[0-9]+: picture file \"../outside.png\" \(accepted: NAME.png, a plain file name" report Q
rj Q "d['pictures'][0]['file'] = 'x.png) [click](http://example'"
t 2 "^brdfbench report: Q/run.json:1:[0-9]+: picture file .* \(accepted: NAME.png" report Q
rj Q "d['pictures'][0]['section'] = 'pie'"
t 2 "^brdfbench report: Q/run.json:1:[0-9]+: unknown section \"pie\" \(heatmaps, plots, throughput, images\)" report Q
rj Q "d['steps'][0]['status'] = 'done'"
t 2 "^brdfbench report: Q/run.json:1:[0-9]+: step status must be \"ok\" or \"failed\"" report Q
rj Q "d['steps'][0]['seconds'] = -1"
t 2 "^brdfbench report: Q/run.json:1:[0-9]+: step \"seconds\" is -1 \(accepted: 0 to 1e9\)" report Q
rj Q "d['steps'][0] = {'name': 'x', 'status': 'failed', 'exit_code': 1e300, 'seconds': 0}"
t 2 "^brdfbench report: Q/run.json:1:[0-9]+: step \"exit_code\" is 1e\+300 \(accepted: a whole number from 1 to 255\)" report Q
rj Q "d['parts']['bogus'] = {'status': 'ok'}"
t 2 "^brdfbench report: Q/run.json:1:[0-9]+: unknown part \"bogus\"" report Q
rj Q "d['parts']['claims'] = {'status': 'missing'}"
t 2 "^brdfbench report: Q/run.json:1:[0-9]+: member \"reason\" is missing" report Q
ff Q claims.json
t 2 "^brdfbench report: Q/claims.json: is a FIFO, not a regular file \(run.json records its part as done\)" report Q
ff Q accuracy.json
t 2 "^brdfbench report: Q/accuracy.json: is a FIFO, not a regular file" report Q
# heatmap: field files fed back
fj H "del d['model']"
t 2 "multi:^brdfbench heatmap: H/field_fq2.json:1:1: member \"model\" is missing" heatmap H
fj H "d['model'] = 5"
t 2 "multi:^brdfbench heatmap: H/field_fq2.json:1:[0-9]+: member \"model\" is a number" heatmap H
# a model the process does not know is redrawn from the field file's own formula (issue 21)
fj H "d['model'] = 'nosuch'"
t 0 "^brdfbench heatmap: 1 picture\(s\) redrawn in H" heatmap H
fj H "d['grid']['rows'] = 1"
t 2 "multi:^brdfbench heatmap: H/field_fq2.json:1:[0-9]+: grid rows/cols must be integers in \[2, 10000\]" heatmap H
fj H "d['grid']['rows'] = 3000; d['grid']['cols'] = 3000"
t 2 "multi:^brdfbench heatmap: H/field_fq2.json:1:[0-9]+: " heatmap H
fj H "d['grid']['n'] = d['grid']['n'][:-1]"
t 2 "multi:^brdfbench heatmap: H/field_fq2.json:1:[0-9]+: \"n\" has 40 values, rows is 41" heatmap H
fj H "d['schema'] = 'brdfbench.field/0'"
t 2 "multi:^brdfbench heatmap: H/field_fq2.json:1:[0-9]+: schema \"brdfbench.field/0\", expected" heatmap H
ff H field_fq2.json
t 2 "multi:^brdfbench heatmap: H/field_fq2.json: is a FIFO, not a regular file" heatmap H
WHAT='H/field_fq2.json: a FIFO'
t 2 "^brdfbench heatmap: --label fq2: H/field_fq2.json: is a FIFO, not a regular file" heatmap H --label fq2
rm H/field_fq2.json && ln -s /dev/urandom H/field_fq2.json
WHAT='H/field_fq2.json -> /dev/urandom'
t 2 "multi:^brdfbench heatmap: H/field_fq2.json: is a character device, not a regular file" heatmap H
truncate -s 200M H/field_fq2.json.big && rm H/field_fq2.json && mv H/field_fq2.json.big H/field_fq2.json
WHAT='H/field_fq2.json: 200 MB'
t 2 "multi:^brdfbench heatmap: H/field_fq2.json: is larger than [0-9]+ bytes \(209715200\)" heatmap H
rm -rf H && mkdir H
t 2 "^brdfbench heatmap: H holds no field_<model>.json to draw from" heatmap H
t 2 "^brdfbench heatmap: --label \.\./fq2: H has no model of that label" heatmap H --label ../fq2
t 2 "^brdfbench heatmap: RUN_DIR 'good.json' is not a folder" heatmap good.json
mkfifo fifo_dir
t 2 "^brdfbench plot: RUN_DIR 'fifo_dir' is not a folder" plot fifo_dir
# compare and gate --baseline: the files of a run that are not what they say
mkdir -p C1 && mkfifo C1/accuracy.json
WHAT='C1/accuracy.json: a FIFO'
t 2 "^brdfbench compare: C1/accuracy.json: is a FIFO, not a regular file" compare base C1 --out run
mkdir -p C2/accuracy.json
WHAT='C2/accuracy.json: a folder'
t 2 "^brdfbench compare: " compare base C2 --out run
t 2 "^brdfbench compare: /dev/null: is a character device, not a regular file" compare base /dev/null --out run
mkdir -p C3 && : >C3/accuracy.json
WHAT='C3/accuracy.json: empty'
t 2 "^brdfbench compare: C3/accuracy.json: empty file" compare base C3 --out run
t 2 "^brdfbench gate: --baseline: C1/accuracy.json: is a FIFO, not a regular file" gate good.json --baseline C1
t 2 "^brdfbench gate: --baseline: /dev/zero: is a character device, not a regular file" gate good.json --baseline /dev/zero
t 2 "^brdfbench gate: --baseline: R0/plots.json: schema \"brdfbench.plots/1\" is not a result file with figures" gate good.json --baseline R0/plots.json
t 2 "^brdfbench gate: --baseline: R0/throughput.json: the figures of throughput.json \(schema brdfbench.throughput/5\), not an accuracy.json \(schema brdfbench.accuracy/3 expected\)" gate good.json --baseline R0/throughput.json
mkdir -p C4
t 2 "^brdfbench gate: --baseline: C4/accuracy.json: cannot open: No such file" gate good.json --baseline C4
python3 -c 'import json; d = json.load(open("base/accuracy.json")); d["results"] = {}; d.pop("rows"); d["schema"] = "brdfbench.accuracy/1"; json.dump(d, open("bad_results.json", "w"))'
t 2 "^brdfbench gate: --baseline: bad_results.json:1:[0-9]+: member \"results\" is an object, an array expected" gate good.json --baseline bad_results.json
# rows: the files and folders it is given, its flags
t 2 "^brdfbench rows: expected FILE\|RUN_DIR \(a result file or a run folder\)" rows
t 2 "^brdfbench rows: unexpected argument 'b'" rows R0 b
t 2 "^brdfbench rows: nothere: no such file or folder \(accepted: a result file or a run folder\)" rows nothere
t 2 "^brdfbench rows: --format: 'xml' is not a format \(accepted: md, csv, json\)" rows R0 --format xml
t 2 "^brdfbench rows: --kind: 'plots' is not a kind of result \(accepted: throughput, accuracy, render, fit, frontier" rows R0 --kind plots
t 2 "^brdfbench rows: --format csv writes one document and R0 holds [0-9]+ \(name one with --kind: throughput, accuracy" rows R0 --format csv
t 2 "^brdfbench rows: --format json writes one document" rows R0 --format json --output rows_out.json
if [ -e rows_out.json ]; then fail=$((fail + 1)); echo "FAIL: rows: a refused run wrote its --output" >&2; fi
t 2 "^brdfbench rows: base: no result file of kind render \(accepted: throughput.json, accuracy.json" rows base --kind render
t 2 "^brdfbench rows: C4: no result file \(accepted: throughput.json, accuracy.json, render.json, fit.json, frontier.json, claims.json, q_sweep.json, physical.json, energy.json, measured.json, or a brdfbench.rows/1 document\)" rows C4
t 2 "^brdfbench rows: C1/accuracy.json: is a FIFO, not a regular file" rows C1
t 2 "^brdfbench rows: good.json:1:1: member \"schema\" is missing" rows good.json
t 2 "^brdfbench rows: R0/plots.json: schema \"brdfbench.plots/1\" is not a result file with figures" rows R0/plots.json
printf '{"schema": "brdfbench.rows/1", "source": {"kind": "accuracy"}, "rows": [{"keys": {}, "metrics": [{"name": "x", "direction": "up"}]}]}' >bad_rows.json
t 2 "^brdfbench rows: bad_rows.json:1:[0-9]+: \"direction\" is \"up\" \(accepted: higher, lower, neither\)" rows bad_rows.json
printf '{"schema": "brdfbench.rows/1", "source": {"kind": "accuracy"}, "rows": [{"keys": {"label": "a|b"}, "metrics": []}]}' >bad_rows.json
t 2 "^brdfbench rows: bad_rows.json:1:[0-9]+: \"label\" holds '\|'" rows bad_rows.json
printf '{"schema": "brdfbench.rows/1", "source": {"kind": "throughput"}, "rows": [{"keys": {}, "metrics": [{"name": "evals_per_s", "direction": "higher", "timed": true, "value": -1}]}]}' >bad_rows.json
t 2 "^brdfbench rows: bad_rows.json:1:[0-9]+: \"value\" is -1 \(accepted: a rate in \[0, 1e\+18\], or null when not measured\)" rows bad_rows.json
printf '{"schema": "brdfbench.rows/1", "source": {"kind": "gates"}, "rows": []}' >bad_rows.json
t 2 "^brdfbench compare: bad_rows.json: rows of kind \"gates\", compare reads throughput, accuracy, render, fit and frontier" compare base bad_rows.json --out run
t 2 "^brdfbench rows: --output: " rows base --output /nonexistent/dir/x.md
# gates files: model files outside their folder, files that are not files, reserved names
mkdir -p gd/sub && cp "$F/scaled.cl" gd/sub/ && cp "$F/scaled.cl" outside.cl && ln -sf ../outside.cl gd/link.cl && mkfifo gd/fifo.cl
printf '{"gates":[{"model":"scaled","model_file":"../outside.cl","metric":"whole.max_abs","max":1}]}' >gd/up.json
printf '{"gates":[{"model":"scaled","model_file":"%s/outside.cl","metric":"whole.max_abs","max":1}]}' "$T" >gd/abs.json
printf '{"gates":[{"model":"scaled","model_file":"link.cl","metric":"whole.max_abs","max":1}]}' >gd/link.json
printf '{"gates":[{"model":"scaled","model_file":"sub/../../outside.cl","metric":"whole.max_abs","max":1}]}' >gd/dots.json
printf '{"gates":[{"model":"fifo","model_file":"fifo.cl","metric":"whole.max_abs","max":1}]}' >gd/fifo.json
printf '{"gates":[{"model":"r","expression":"brdf_user_eval(c,n,p0,p1)","metric":"whole.max_abs","max":1}]}' >gd/wrapper.json
printf '{"gates":[{"model":"r","expression":"brdfbench_host_eval(c,n,0,0)","metric":"whole.max_abs","max":1}]}' >gd/host_eval.json
printf '{"gates":[{"model":"brdf_r","expression":"c","metric":"whole.max_abs","max":1}]}' >gd/name.json
printf '{"timeout": "10", "gates":[{"model":"fq2","metric":"whole.max_abs","max":1}]}' >gd/timeout_string.json
printf '{"timeout": 1e9, "gates":[{"model":"fq2","metric":"whole.max_abs","max":1}]}' >gd/timeout_big.json
t 2 "^brdfbench gate: gd/up.json:1:[0-9]+: gate 1: \"model_file\" '../outside.cl' lies outside the gates file's folder gd; a model file is a program" gate gd/up.json
t 2 "^brdfbench gate: gd/abs.json:1:[0-9]+: gate 1: \"model_file\" '.*outside.cl' lies outside the gates file's folder gd" gate gd/abs.json
t 2 "^brdfbench gate: gd/link.json:1:[0-9]+: gate 1: \"model_file\" 'link.cl' lies outside the gates file's folder gd" gate gd/link.json
t 2 "^brdfbench gate: gd/dots.json:1:[0-9]+: gate 1: \"model_file\" 'sub/../../outside.cl' lies outside" gate gd/dots.json
t 2 "^brdfbench gate: gd/fifo.json:1:[0-9]+: gate 1: --model-file: cannot read gd/fifo.cl: is a FIFO, not a regular file" gate gd/fifo.json
t 2 "^brdfbench gate: gd/wrapper.json:1:[0-9]+: gate 1: --model r: character 1: identifier 'brdf_user_eval' is reserved" gate gd/wrapper.json
t 2 "^brdfbench gate: gd/host_eval.json:1:[0-9]+: gate 1: --model r: character 1: identifier 'brdfbench_host_eval' is reserved" gate gd/host_eval.json
t 2 "^brdfbench gate: gd/name.json:1:[0-9]+: gate 1: --model: name 'brdf_r' is not an identifier .* or is reserved" gate gd/name.json
t 2 "^brdfbench gate: gd/timeout_string.json:1:[0-9]+: \"timeout\" is a string, a number expected" gate gd/timeout_string.json
t 2 "^brdfbench gate: gd/timeout_big.json:1:[0-9]+: \"timeout\" 1e\+09 is out of range \(accepted: seconds in \[0.01, 604800\]\)" gate gd/timeout_big.json
t 2 "^brdfbench gate: /dev/zero: cannot read the gates file: is a character device, not a regular file" gate /dev/zero
truncate -s 5M big_gates.json
t 2 "^brdfbench gate: big_gates.json: larger than 4 MiB" gate big_gates.json
t 2 "^brdfbench gate: /dev/fd/[0-9]+:1:[0-9]+: \"gates\" has 0 gates" gate <(printf '{"gates": []}')
# --kernel-dir: a FIFO, a folder or nothing where brdf_models.h should be
mkdir -p K1 && mkfifo K1/brdf_models.h && mkdir -p K2/brdf_models.h
t 2 "^brdfbench accuracy: --kernel-dir: K1/brdf_models.h is a FIFO, not a regular file \(accepted: a kernels/ folder\)" accuracy --kernel-dir K1
t 2 "^brdfbench accuracy: --kernel-dir: K2/brdf_models.h is a folder, not a file" accuracy --kernel-dir K2
t 2 "^brdfbench accuracy: --kernel-dir: good.json does not hold brdf_models.h" accuracy --kernel-dir good.json
# user-model expressions: brdfbench's own names, characters, lengths
t 2 "^brdfbench accuracy: --model r: character 1: identifier 'brdf_user_eval' is reserved \(brdf_\*, BRDF_\* and brdfbench_\*" accuracy --model 'r=brdf_user_eval(c,n,p0,p1)' --n-max 10
t 2 "^brdfbench accuracy: --model r: character 5: identifier 'brdf_eval' is reserved" accuracy --model 'r=c + brdf_eval(0, c, n, 0, 0)'
t 2 "^brdfbench accuracy: --model r: character 1: identifier 'brdf_eval_s' is reserved" accuracy --model 'r=brdf_eval_s(0, 1 - c, n, 0, 0)'
t 2 "^brdfbench accuracy: --model r: character 3: identifier 'BRDF_PI' is reserved" accuracy --model 'r=c*BRDF_PI'
t 2 "^brdfbench accuracy: --model r: character 8: identifier 'brdf_x' is reserved" accuracy --model 'r=1e5f*c+brdf_x'
t 2 "^brdfbench render: --model r: character 1: identifier 'brdf_user_eval' is reserved" render --model 'r=brdf_user_eval(c,n,0,0)'
t 2 "^brdfbench throughput: --model r: character 1: identifier 'brdf_user_eval' is reserved" throughput --model 'r=brdf_user_eval(c,n,0,0)'
t 2 "^brdfbench all: --model r: character 1: identifier 'brdf_user_eval' is reserved" all --model 'r=brdf_user_eval(c,n,0,0)'
t 2 "^brdfbench accuracy: --model: name 'brdf_q' is not an identifier" accuracy --model 'brdf_q=c'
t 2 "^brdfbench accuracy: --model: name 'c' is not an identifier" accuracy --model 'c=c'
t 2 "^brdfbench accuracy: --model: name 'n' is not an identifier" accuracy --model 'n=c'
t 2 "^brdfbench accuracy: --model: the name before '=' must have 1 to 48 characters" accuracy --model "$(printf 'a%.0s' {1..49})=c"
t 2 "^brdfbench accuracy: --model: the name before '=' must have 1 to 48 characters" accuracy --model '=c'
t 2 "^brdfbench accuracy: --model: name 'a b' is not an identifier" accuracy --model 'a b=c'
t 2 "^brdfbench accuracy: --model e: character 1 of the expression is not allowed" accuracy --model "e=$(printf '\xc3\xa9')"
t 2 "^brdfbench accuracy: --model e: character 2 of the expression is not allowed" accuracy --model 'e=c#n'
t 2 "^brdfbench accuracy: --model e: the expression must have 1 to 1000 characters" accuracy --model "e=$(printf 'c%.0s' {1..1001})"
t 2 "^brdfbench accuracy: --model e: the expression is blank" accuracy --model 'e=   '
# model files: recursion, pasting, reserved names, files that are not files, limits
mk() { printf '/* brdfbench-model\n * name: %s\n */\n%b' "$1" "$2" >"$1.cl"; }
mk self 'REAL self(REAL c, REAL n) { return c > 2 ? self(c, n) : c; }\n'
mk mut '#define G(c, n) mut(c, n)\nREAL h(REAL c, REAL n) { return G(c, n); }\nREAL mut(REAL c, REAL n) { return c > 2 ? h(c, n) : c; }\n'
mk paste '#define CAT(a, b) a##b\nREAL paste(REAL c, REAL n) { return CAT(c, ) * n; }\n'
mk cont 'REAL cont(REAL c, REAL n) { return brdf_user_\\\neval(c, n, 0, 0); }\n'
mk disp 'REAL disp(REAL c, REAL n) { return brdf_eval(0, c, n, 0, 0); }\n'
mk macro '#define W brdf_user_eval\nREAL macro(REAL c, REAL n) { return W(c, n, 0, 0); }\n'
mk bench 'REAL bench(REAL c, REAL n) { return brdfbench_host_eval(c, n, 0, 0); }\n'
mk helper 'REAL helper(REAL c, REAL n) { return brdf_quadratic_s(1 - c, n); }\n'
printf '/* brdfbench-model\n * name: brdf_mine\n */\nREAL brdf_mine(REAL c, REAL n) { return c; }\n' >name_reserved.cl
printf '/* brdfbench-model\n * name: fn\n * function: brdf_user_eval\n */\nREAL x(REAL c, REAL n) { return c; }\n' >fn_reserved.cl
printf '/* brdfbench-model\n * name: pc\n * param: c 0 1 0.5\n */\nREAL pc(REAL c, REAL n, RSCALAR k) { return c; }\n' >param_c.cl
printf '/* brdfbench-model\n * name: p3\n * param: a 0 1 0.5\n * param: b 0 1 0.5\n * param: d 0 1 0.5\n */\nREAL p3(REAL c, REAL n) { return c; }\n' >p3.cl
printf '/* brdfbench-model\n * name: dn\n * name: dn\n */\nREAL dn(REAL c, REAL n) { return c; }\n' >twice.cl
printf '/* brdfbench-model\n * name: rf\n * reference: nosuch\n */\nREAL rf(REAL c, REAL n) { return c; }\n' >ref.cl
printf '/* brdfbench-model\n * name: lb\n * lobe: phi\n */\nREAL lb(REAL c, REAL n) { return c; }\n' >lobe.cl
printf '/* brdfbench-model\n * name: df\n * param: k 0 1 2\n */\nREAL df(REAL c, REAL n, RSCALAR k) { return c; }\n' >default.cl
printf '/* brdfbench-model\n * name: di\n * param: k 0 10 2.5 integer\n */\nREAL di(REAL c, REAL n, RSCALAR k) { return c; }\n' >default_int.cl
printf '/* brdfbench-model\n * name: un\n REAL un(REAL c, REAL n) { return c; }\n' >unterminated.cl
printf '/* brdfbench-model\n * name: nul\n */\nREAL nul(REAL c, REAL n) { return c; }\n\000\n' >nul.cl
: >empty.cl
{ printf '/* brdfbench-model\n * name: huge\n */\n'; head -c 300000 /dev/zero | tr '\0' ' '; printf 'REAL huge(REAL c, REAL n) { return c; }\n'; } >huge.cl
mkfifo fifo.cl
t 2 "^brdfbench accuracy: self.cl:4: 'self' calls itself \(self -> self\): OpenCL C has no recursion" accuracy --model-file self.cl
t 2 "^brdfbench accuracy: mut.cl:4: 'G' calls itself \(G -> mut -> h -> G\): OpenCL C has no recursion" accuracy --model-file mut.cl
t 2 "^brdfbench accuracy: paste.cl:4: token pasting \(##\) is not accepted in a user model" accuracy --model-file paste.cl
t 2 "^brdfbench accuracy: cont.cl:4: identifier 'brdf_user_eval' is reserved" accuracy --model-file cont.cl
t 2 "^brdfbench accuracy: disp.cl:4: identifier 'brdf_eval' is reserved" accuracy --model-file disp.cl
t 2 "^brdfbench accuracy: macro.cl:4: identifier 'brdf_user_eval' is reserved" accuracy --model-file macro.cl
t 2 "^brdfbench accuracy: bench.cl:4: identifier 'brdfbench_host_eval' is reserved" accuracy --model-file bench.cl
t 2 "^brdfbench accuracy: helper.cl:4: identifier 'brdf_quadratic_s' is reserved .*only the helpers brdf_quadratic, " accuracy --model-file helper.cl
t 2 "^brdfbench accuracy: name_reserved.cl:2: name 'brdf_mine' is not an identifier of 1 to 48 characters .* or is reserved" accuracy --model-file name_reserved.cl
t 2 "^brdfbench accuracy: fn_reserved.cl:3: function 'brdf_user_eval' is not an identifier of 1 to 48 characters or is reserved" accuracy --model-file fn_reserved.cl
t 2 "^brdfbench accuracy: param_c.cl:3: parameter name 'c' is not an identifier of 1 to 48 characters or is reserved" accuracy --model-file param_c.cl
t 2 "^brdfbench accuracy: p3.cl:5: more than 2 parameters \(accepted: 0 to 2\)" accuracy --model-file p3.cl
t 2 "^brdfbench accuracy: twice.cl:3: 'name' is declared twice" accuracy --model-file twice.cl
t 2 "^brdfbench accuracy: ref.cl:3: reference 'nosuch' is not a built-in model" accuracy --model-file ref.cl
t 2 "^brdfbench accuracy: lobe.cl:3: lobe 'phi' is unknown \(accepted: psi, theta_h\)" accuracy --model-file lobe.cl
t 2 "^brdfbench accuracy: default.cl:3: parameter 'k': DEFAULT 2 is not a number in \[0, 1\]" accuracy --model-file default.cl
t 2 "^brdfbench accuracy: default_int.cl:3: parameter 'k': DEFAULT 2.5 is not an integer in \[0, 10\]" accuracy --model-file default_int.cl
t 2 "^brdfbench accuracy: unterminated.cl:1: a model file begins with a header comment" accuracy --model-file unterminated.cl
t 2 "^brdfbench accuracy: nul.cl: NUL byte in a model file \(a text file is expected\)" accuracy --model-file nul.cl
t 2 "^brdfbench accuracy: empty.cl: empty model file" accuracy --model-file empty.cl
t 2 "^brdfbench accuracy: huge.cl: larger than 65536 bytes" accuracy --model-file huge.cl
t 2 "^brdfbench accuracy: --model-file: cannot read fifo.cl: is a FIFO, not a regular file" accuracy --model-file fifo.cl
t 2 "^brdfbench accuracy: --model-file: cannot read /dev/zero: is a character device, not a regular file" accuracy --model-file /dev/zero
t 2 "^brdfbench accuracy: --model-file: cannot read /dev/null: is a character device, not a regular file" accuracy --model-file /dev/null
t 2 "^brdfbench accuracy: --model-file: cannot read /dev/stdin: is a " accuracy --model-file /dev/stdin
cp self.cl self2.cl && sed -i 's/self/other/g' self2.cl && cp "$F/scaled.cl" scaled_copy.cl
t 2 "^brdfbench accuracy: scaled_copy.cl: user model 'scaled' is already defined by .*scaled.cl" accuracy --model-file "$F/scaled.cl" --model-file scaled_copy.cl
# names that become file and folder names: what --out may be for all, which replaces it whole
mkdir -p own && echo mine >own/notes.sh && mkdir -p own2/src && mkfifo own3_fifo && mkdir -p own3 && mv own3_fifo own3/x.json
t 2 "^brdfbench all: --out: own holds 'notes.sh', which is no part of a brdfbench run" all --quick --out own
t 2 "^brdfbench all: --out: own2 holds 'src', which is no part of a brdfbench run" all --quick --out own2
t 2 "^brdfbench all: --out: own3 holds 'x.json', which is no part of a brdfbench run" all --quick --out own3
t 2 "^brdfbench all: --out: \. is the working folder or holds it" all --quick --out .
t 2 "^brdfbench all: --out: / is the working folder or holds it" all --quick --out /
t 2 "^brdfbench all: --out: \.\. is the working folder or holds it" all --quick --out ..
t 3 "^brdfbench all: --out: good.json is not a folder" all --quick --out good.json
t 3 "^brdfbench all: --out: /dev/null is not a folder" all --quick --out /dev/null
t 3 "^brdfbench all: --out: cannot create folder /proc/brdf/x: " all --quick --out /proc/brdf/x
mkdir -p rl/latest && mkdir -p rf && echo mine >rf/latest
t 3 "^brdfbench all: rl/latest is a folder, not the symlink to the latest run that brdfbench keeps there" all --quick --results-root rl
t 3 "^brdfbench all: rf/latest is a file, not the symlink to the latest run that brdfbench keeps there" all --quick --results-root rf
t 3 "^brdfbench all: good.json is not a folder" all --quick --results-root good.json
# --json and --csv: a place that cannot take the file fails before the work
t 3 "^brdfbench accuracy: --json: folder nowhere does not exist" accuracy --json nowhere/acc.json
t 3 "^brdfbench accuracy: --csv: folder nowhere does not exist" accuracy --csv nowhere/acc.csv
t 3 "^brdfbench accuracy: --json: folder is a folder \(a file name is expected\)" accuracy --json folder
t 3 "^brdfbench accuracy: --json: cannot write good.json/x.json: Not a directory" accuracy --json good.json/x.json
t 3 "^brdfbench throughput: --json: folder nowhere does not exist" throughput --json nowhere/tp.json
t 3 "^brdfbench throughput: --csv: folder nowhere does not exist" throughput --csv nowhere/tp.csv
t 3 "^brdfbench fit: --json: folder nowhere does not exist" fit --json nowhere/fit.json
ln -sf nowhere/dangling.json dangling.json
t 3 "^brdfbench accuracy: --json: folder nowhere does not exist" accuracy --json dangling.json
t 2 "^brdfbench render: --csv: render writes no CSV; the rows of several devices are gathered into render.json" render --device all --csv x.csv
t 2 "^brdfbench accuracy: --json - and --csv -: one document at a time on standard output" accuracy --device all --json - --csv -
# scene files: devices, folders, FIFOs, binary or huge files are refused before they are read
mkfifo scene.fifo && truncate -s 300M sparse.pov && printf 'ply\n\000binary' >bin.pov
t 2 "^brdfbench render: /dev/zero: cannot read: is a character device, not a regular file" render --scene teapot --teapot-file /dev/zero --out run
t 2 "^brdfbench render: /tmp: cannot read: is a folder, not a file" render --scene teapot --teapot-file /tmp --out run
t 2 "^brdfbench render: scene.fifo: cannot read: is a FIFO, not a regular file" render --scene teapot --teapot-file scene.fifo --out run
t 2 "^brdfbench render: sparse.pov: 314572800 bytes, larger than a scene file may be" render --scene teapot --teapot-file sparse.pov --out run
t 2 "^brdfbench render: bin.pov:2: not a POV-Ray file \(expected a text file with bicubic_patch blocks\); found binary data" render --scene teapot --teapot-file bin.pov --out run
t 2 "^brdfbench render: /dev/urandom: cannot read: is a character device, not a regular file" render --scene bunny --bunny-file /dev/urandom --out run
t 2 "^brdfbench render: sparse.pov: 314572800 bytes, larger than a scene file may be" render --scene bunny --bunny-file sparse.pov --out run
t 2 "^brdfbench render: folder: cannot read: is a folder, not a file" render --scene bunny --bunny-file folder --out run
t 2 "^brdfbench render: bunny scene: cannot read nothere.obj: No such file" render --scene bunny --bunny-file nothere.obj --out run
# limits
t 2 "^brdfbench accuracy: --timeout: '1e-9' is not a finite number in \[0.01, 604800\]" accuracy --timeout 1e-9
t 2 "^brdfbench accuracy: --timeout: '700000' is not a finite number in \[0.01, 604800\]" accuracy --timeout 700000
t 2 "^brdfbench accuracy: --timeout: '-1' is not a finite number" accuracy --timeout -1
t 2 "^brdfbench accuracy: --timeout: '5s' is not a finite number" accuracy --timeout 5s
t 2 "^brdfbench accuracy: --samples: '4194320' is not an integer in \[16, 4194304\]" accuracy --samples 4194320
t 2 "^brdfbench accuracy: --n-step: 1e-300 gives .* values of n \(accepted: 2 to 10000000\)" accuracy --n-step 1e-300
t 2 "^brdfbench accuracy: --n-max: '1e6x' is not a finite number" accuracy --n-max 1e6x
t 2 "^brdfbench render: --size: '16385x16' is not WxH" render --size 16385x16
t 2 "^brdfbench render: --size: '99999999999x1' is not WxH" render --size 99999999999x1
t 2 "^brdfbench render: --exposure: '1e400' is not a finite number" render --exposure 1e400
t 2 "^brdfbench accuracy: --platform: '64' is not an integer in \[0, 63\]" accuracy --platform 64
t 2 "^brdfbench accuracy: --model z9: at most 8 user models per run" accuracy --model z1=c --model z2=c --model z3=c --model z4=c --model z5=c --model z6=c --model z7=c --model z8=c --model z9=c
# environments
t 2 "^brdfbench accuracy: --n-min: '0,5' is not a finite number" LC_ALL=C.UTF-8 accuracy --n-min 0,5
t 3 "^brdfbench accuracy: --json -: cannot make a temporary folder in /nonexistent \(TMPDIR\): No such file or directory" TMPDIR=/nonexistent accuracy --models fq2 --n-max 4 --samples 16 --json -
t 77 "^brdfbench accuracy: no OpenCL platform found" OCL_ICD_VENDORS=/nonexistent accuracy --models fq2 --n-max 4 --samples 16 --out run
t 2 "^brdfbench accuracy: POCL_CACHE_DIR=good.json is not a writable folder \(PoCL keeps its compiled kernels there" POCL_CACHE_DIR=good.json accuracy --models fq2 --n-max 4 --samples 16 --out run
t 77 "^brdfbench accuracy: no OpenCL device found: platform '.*' reports none; POCL_DEVICES=nosuch selects the devices" POCL_DEVICES=nosuch accuracy --models fq2 --n-max 4 --samples 16 --out run
t 2 "^brdfbench accuracy: --out: empty path" POCL_DEVICES= accuracy --out ''

# ---- issue 23, the rest: rows lost between runs, figures fed back, names that share a file,
# models that are NaN. R0 (all --quick, above) is the baseline; each row edits a copy of it.
# jd DIR FILE PYTHON: a copy of R0 as DIR with PYTHON run on DIR/FILE (as d; its rows as rows:
# results, models, scenes, or fit.json's compare list)
jd() {
    WHAT="$1/$2: $3"
    rm -rf "$1" && cp -r R0 "$1"
    python3 - "$1/$2" "$3" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
rows = d.get("results") or d.get("models") or d.get("scenes") or d.get("compare") or []
exec(sys.argv[2])
# the layout edited: the file in the previous version's form (no "rows" member), read by that
# layout (a current file's rows member would not show the edit)
PREV = {"brdfbench.throughput/5": "brdfbench.throughput/3", "brdfbench.render/3": "brdfbench.render/1",
        "brdfbench.fit/3": "brdfbench.fit/1", "brdfbench.frontier/3": "brdfbench.frontier/1",
        "brdfbench.accuracy/3": "brdfbench.accuracy/1"}
if d.get("schema") in PREV:
    d.pop("rows", None)
    d["schema"] = PREV[d["schema"]]
json.dump(d, open(sys.argv[1], "w"))
PY
}
CF="--fail-if-less-accurate --fail-if-slower 90 --out cmpo --quiet"
W="multi:^brdfbench compare: warning: a rate has only"   # R0 is --quick: one repetition per rate
# Identical runs never fail, also when the fit moved: the fitted quadratic's label
# quad:a=...,b=... moves with its coefficients, and its row is matched by its role.
t 0 "$W" compare R0 R0 $CF
jd N fit.json "for c in d['compare']: c['model'] = c['model'].replace('quad:a=0.4', 'quad:a=0.5')"
t 0 "$W" compare R0 N $CF
jd N fit.json "d['a'] = d['a'] * 1.00001"
t 0 "$W" compare R0 N --fail-if-slower 90 --out cmpo --quiet
# A row of the baseline that the new run lost: exit 1, the row named with what happened.
# cl FILE PYTHON PATTERN: R0 against a copy whose FILE PYTHON edits: exit 1 and "N: PATTERN"
cl() {
    jd N "$1" "$2"
    t 1 "multi:^N: $3" compare R0 N $CF
}
cl accuracy.json "rows[0]['status'] = 'failed'" "accuracy fq2 \| n 2\.\.1000 .* epicentre\.max_rel: failed \(the baseline has 0\.01"
cl accuracy.json "rows[0]['status'] = 'device_disagrees'; rows[0]['reason'] = 'device and double disagree'" "accuracy fq2 .* attenuation\.max_abs: device and double disagree \(the baseline has"
cl accuracy.json "rows[0]['status'] = 'device_disagrees'" "accuracy fq2 .* whole\.max_abs: device_disagrees"
cl accuracy.json "del rows[0]" "accuracy fq2 .* epicentre\.max_rel: missing from this run"
cl accuracy.json "rows[0]['epicentre']['max_rel'] = None" "accuracy fq2 .* epicentre\.max_rel: not a finite number"
cl throughput.json "del rows[2]" "throughput fq2 \| default \| n uniform evals_per_s: missing from this run"
cl throughput.json "rows[3]['status'] = 'failed'; rows[3]['reason'] = 'the kernel failed'" "throughput fq2 \| default \| n varying evals_per_s: the kernel failed"
cl throughput.json "del d['peak']" "throughput peak \(reference kernel\) flops_per_s: missing from this run"
cl render.json "rows[0]['models'] = []" "render spheres [0-9]+x[0-9]+ \| fq2 max_abs: missing from this run"
cl render.json "rows[1]['models'][0]['metrics']['status'] = 'nonfinite'; rows[1]['models'][0]['metrics']['reason'] = 'NaN pixels'" "render teapot [0-9]+x[0-9]+ \| fq2 rmse: NaN pixels"
cl render.json "rows[2]['timings'][0]['entries'] = [e for e in rows[2]['timings'][0]['entries'] if e.get('model') != 'fq2']" "render bunny \| fq2 mpixel_per_s@[0-9]+x[0-9]+: missing from this run"
cl fit.json "d['compare'] = [c for c in rows if c['model'] != 'fq2']" "fit fq2 \| n .* max_rel: missing from this run"
cl fit.json "d['status'] = 'failed'; d['reason'] = 'no fit'" "fit best affine k\(n\) \| n .* max_rel: no fit"
cl frontier.json "d['models'] = []" "frontier fq2 n_2_1000\.max_rel: missing from this run"
cl frontier.json "rows[0]['psnr_db'] = None" "frontier fq2 psnr_db: not a finite number"
# ... but only under the condition that watches it, and only when the baseline had it
jd N accuracy.json "del rows[0]"
t 0 "$W" compare R0 N --fail-if-slower 90 --out cmpo --quiet
jd N throughput.json "del rows[2]"
t 0 "$W" compare R0 N --fail-if-less-accurate --out cmpo --quiet
jd N accuracy.json "rows[0]['status'] = 'failed'"
t 0 "$W" compare N N $CF
t 0 "$W" compare N R0 $CF
t 1 "multi:^N: accuracy fq2 .* failed \(the baseline" compare R0 R0 N $CF

# Figures compare refuses (exit 2, naming the file, line, column and member): negative,
# absurd and non-numeric figures, labels that break a table, rows given twice.
# cj FILE PYTHON PATTERN: R0 against a copy whose FILE PYTHON edits: exit 2 and PATTERN after
# "FILE:LINE:COL: " (or "FILE: ")
cj() {
    jd N "$1" "$2"
    t 2 "^brdfbench compare: N/$1(:[0-9]+:[0-9]+)?: $3" compare R0 N --out cmpo
}
cj throughput.json "rows[0]['evals_per_s']['median'] = -5" '"median" is -5 \(accepted: a rate in \[0, 1e\+18\]'
cj throughput.json "rows[0]['evals_per_s']['median'] = 1e308" '"median" is 1e\+308 \(accepted: a rate'
cj throughput.json "rows[0]['evals_per_s']['max'] = 1e19" '"max" is 1e\+19 \(accepted: a rate'
cj throughput.json "rows[0]['evals_per_s']['median'] = '1e9'" '"median" is a string \(accepted: a number, or null'
cj throughput.json "rows[0]['evals_per_s']['median'] = True" '"median" is a boolean'
cj throughput.json "rows[0]['evals_per_s']['median'] = [1]" '"median" is not a number'
cj throughput.json "rows[0]['evals_per_s_reps'][0] = -1" '"evals_per_s_reps" is -1 \(accepted: a rate'
cj throughput.json "rows[0]['evals_per_s_reps'][0] = 'fast'" '"evals_per_s_reps" holds a value that is not a number'
cj throughput.json "rows[0]['evals_per_s_reps'][0] = None" '"evals_per_s_reps" holds a value that is not a number'
cj throughput.json "rows[0]['normalised_reps'] = [-0.5]" '"normalised_reps" is -0.5'
cj throughput.json "d['peak']['flops_per_s']['median'] = -1" '"median" is -1 \(accepted: a rate'
cj accuracy.json "rows[0]['epicentre']['max_rel'] = -1" '"max_rel" is -1 \(accepted: an error in \[0, 1e\+100\]'
cj accuracy.json "rows[0]['epicentre']['max_rel'] = 1e308" '"max_rel" is 1e\+308 \(accepted: an error'
cj accuracy.json "rows[0]['attenuation']['max_abs'] = '0.1'" '"max_abs" is a string'
cj accuracy.json "rows[0]['whole']['max_abs'] = -1e-9" '"max_abs" is -1e-09'
cj accuracy.json "rows[0]['epicentre']['max_rel'] = False" '"max_rel" is a boolean'
cj render.json "rows[0]['models'][0]['metrics']['max_abs'] = -1" '"max_abs" is -1 \(accepted: an error'
cj render.json "rows[0]['models'][0]['metrics']['rmse'] = 1e200" '"rmse" is 1e\+200'
cj render.json "rows[0]['models'][0]['metrics']['psnr_db'] = 1e6" '"psnr_db" is 1e\+06 \(accepted: a PSNR in \[-1000, 1000\] dB'
cj render.json "rows[0]['models'][0]['metrics']['psnr_db'] = 'high'" '"psnr_db" is a string'
cj render.json "rows[0]['timings'][0]['entries'][0]['mpixel_per_s'] = -3" '"mpixel_per_s" is -3 \(accepted: a rate'
cj render.json "rows[0]['models'][0]['metrics']['mean_abs'] = -2" '"mean_abs" is -2'
cj fit.json "d['max_rel'] = -1" '"max_rel" is -1 \(accepted: an error'
cj fit.json "rows[2]['max_abs'] = 'small'" '"max_abs" is a string'
cj fit.json "d['capped_at_fq2']['max_rel'] = 1e308" '"max_rel" is 1e\+308'
cj frontier.json "rows[0]['n_2_1000']['max_abs'] = 1e300" '"max_abs" is 1e\+300 \(accepted: an error'
cj frontier.json "rows[0]['psnr_db'] = 5000" '"psnr_db" is 5000 \(accepted: a PSNR'
cj frontier.json "rows[0]['n_2_1000']['max_rel'] = -1" '"max_rel" is -1 \(accepted: an error'
cj frontier.json "rows[0]['n_16_1000']['max_abs'] = '0'" '"max_abs" is a string'
cj accuracy.json "rows[0]['label'] = 'fq2\nx'" '"label" holds a newline \(accepted: one line of text without '\''\|'\'''
cj accuracy.json "rows[0]['label'] = 'fq2 | x'" '"label" holds '\''\|'\'', which would break the table'
cj accuracy.json "rows[0]['device'] = 'cpu\x1b[31m'" '"device" holds a control character'
cj throughput.json "rows[0]['label'] = 'pow\tx'" '"label" holds a control character'
cj throughput.json "rows[0]['variant'] = 'a|b'" '"variant" holds '\''\|'\'''
cj throughput.json "rows[0]['n_mode'] = 'uni\rform'" '"n_mode" holds a control character'
cj render.json "rows[0]['scene'] = 'sph\neres'" '"scene" holds a newline'
cj render.json "rows[0]['models'][0]['model'] = 'fq2|'" '"model" holds '\''\|'\'''
cj frontier.json "rows[0]['model'] = 'fq2\n| x |'" '"model" holds a newline'
cj fit.json "rows[2]['model'] = 'fq2\n'" '"model" holds a newline'
cj accuracy.json "d['results'].append(dict(rows[0]))" 'the row fq2 \| n 2\.\.1000 .* \(epicentre\.max_rel\) appears twice \(accepted: one row per key'
cj throughput.json "d['results'].append(dict(rows[2]))" 'the row fq2 \| default \| n uniform \(evals_per_s\) appears twice'
cj frontier.json "d['models'].append(dict(rows[0]))" 'the row fq2 \(n_2_1000\.max_rel\) appears twice'
cj render.json "rows[0]['models'].append(dict(rows[0]['models'][0]))" 'the row spheres [0-9]+x[0-9]+ \| fq2 \(max_abs\) appears twice'
cj fit.json "d['compare'].append(dict(rows[2]))" 'the row fq2 \| n .* \(max_rel\) appears twice'
cj accuracy.json "d['results'] = [rows[0]] * 3" 'the row fq2 .* appears twice'
cj throughput.json "rows[0]['evals_per_s']['min'] = -1e-300" '"min" is -1e-300 \(accepted: a rate'
cj throughput.json "d['peak']['flops_per_s_reps'] = [1, -2]" '"flops_per_s_reps" is -2 \(accepted: a rate'
cj throughput.json "rows[0]['device'] = 'gpu | 0'" '"device" holds '\''\|'\'''
cj render.json "rows[0]['timings'][0]['entries'][0]['mpixel_per_s'] = 1e300" '"mpixel_per_s" is 1e\+300 \(accepted: a rate'
cj render.json "rows[0]['timings'][0]['entries'][0]['mpixel_per_s_reps'] = ['x']" '"mpixel_per_s_reps" holds a value that is not a number'
cj render.json "rows[0]['models'][0]['metrics']['rmse'] = [0.1]" '"rmse" is not a number'
cj accuracy.json "rows[0]['epicentre']['max_rel'] = {'v': 1}" '"max_rel" is not a number'
cj accuracy.json "rows[0]['label'] = 'fq2\x7f'" '"label" holds a control character'
cj frontier.json "rows[0]['psnr_db'] = -2000" '"psnr_db" is -2000 \(accepted: a PSNR'
cj fit.json "d['max_abs'] = 1e101" '"max_abs" is 1e\+101 \(accepted: an error in \[0, 1e\+100\]'
# compare reads at most 16 runs (CMP_MAX_RUNS): the 17th is refused before any is read
t 2 "^brdfbench compare: at most 16 runs \(accepted: 1 to 16\)" compare R0 R0 R0 R0 R0 R0 R0 R0 R0 R0 R0 R0 R0 R0 R0 R0 R0 --out cmpo

# Names that become file names: two user models that would write one file are refused when
# the second is defined (field_NAME.json and heatmap_NAME.png drop '_'; render writes
# NAME_error.png and NAME_contact.png beside NAME.png, and contact.png and he_*.png of its own).
N2="user model '%s': its files would be those of model '%s'"
t 2 "^brdfbench accuracy: --model xy: user model 'xy': its files would be those of model 'x_y' \(field_xy.json and heatmap_xy.png\); rename one of the two" accuracy --model 'x_y=c' --model 'xy=c*c' --out run
t 2 "^brdfbench accuracy: --model x_y: user model 'x_y': its files would be those of model 'xy' \(field_xy.json" accuracy --model 'xy=c' --model 'x_y=c*c' --out run
t 2 "^brdfbench accuracy: --model x__y: user model 'x__y': its files would be those of model 'x_y'" accuracy --model 'x_y=c' --model 'x__y=c*c' --out run
t 2 "^brdfbench accuracy: --model fq_2: user model 'fq_2': its files would be those of model 'fq2' \(field_fq2.json" accuracy --model 'fq_2=c*c' --out run
t 2 "^brdfbench accuracy: --model _fq2: user model '_fq2': its files would be those of model 'fq2'" accuracy --model '_fq2=c*c' --out run
t 2 "^brdfbench accuracy: --model fq2_: user model 'fq2_': its files would be those of model 'fq2'" accuracy --model 'fq2_=c*c' --out run
t 2 "^brdfbench accuracy: --model phong_n: user model 'phong_n': its files would be those of model 'phongn'" accuracy --model 'phong_n=c' --out run
t 2 "^brdfbench accuracy: --model c_q_2: user model 'c_q_2': its files would be those of model 'cq2'" accuracy --model 'c_q_2=c' --out run
t 2 "^brdfbench render: --model fq2_error: user model 'fq2_error': its files would be those of model 'fq2' \(render's fq2_error.png\)" render --model 'fq2_error=c*c' --out run
t 2 "^brdfbench render: --model fq2_contact: user model 'fq2_contact': its files would be those of model 'fq2' \(render's fq2_contact.png\)" render --model 'fq2_contact=c*c' --out run
t 2 "^brdfbench render: --model a: user model 'a': its files would be those of model 'a_error' \(render's a_error.png\)" render --model 'a_error=c' --model 'a=c*c' --out run
t 2 "^brdfbench render: --model b_contact: user model 'b_contact': its files would be those of model 'b' \(render's b_contact.png\)" render --model 'b=c' --model 'b_contact=c*c' --out run
t 2 "^brdfbench render: --model contact: user model 'contact': the name is a file name render keeps for itself \(contact, he_\*\)" render --model 'contact=c' --out run
t 2 "^brdfbench render: --model he_fq2: user model 'he_fq2': the name is a file name render keeps for itself" render --model 'he_fq2=c' --out run
t 2 "^brdfbench all: --model xy: user model 'xy': its files would be those of model 'x_y'" all --quick --model 'x_y=c' --model 'xy=c*c' --out run
t 2 "^brdfbench throughput: --model fq_2: user model 'fq_2': its files would be those of model 'fq2'" throughput --model 'fq_2=c' --out run
t 2 "^brdfbench frontier: --model he_x: user model 'he_x': the name is a file name render keeps" frontier --model 'he_x=c' --out run
t 2 "^brdfbench accuracy: --model fq2_error: user model 'fq2_error': its files would be those of model 'fq2'" accuracy --model 'fq2_error=c' --out run
t 2 "^brdfbench accuracy: --model he_: user model 'he_': the name is a file name render keeps for itself" accuracy --model 'he_=c' --out run
t 2 "^brdfbench accuracy: --model f_v_o_l: user model 'f_v_o_l': its files would be those of model 'fvol'" accuracy --model 'f_v_o_l=c' --out run
t 2 "^brdfbench accuracy: --model blinn_n: user model 'blinn_n': its files would be those of model 'blinnn'" accuracy --model 'blinn_n=c' --out run
t 2 "^brdfbench accuracy: --model phongn_contact: user model 'phongn_contact': its files would be those of model 'phongn' \(render's phongn_contact.png\)" accuracy --model 'phongn_contact=c' --out run
printf '{"gates":[{"model":"x_y","expression":"c","metric":"whole.max_abs","max":1},{"model":"xy","expression":"c*c","metric":"whole.max_abs","max":1}]}' >clash2_gate.json
t 2 "^brdfbench gate: clash2_gate.json:1:[0-9]+: gate 2: .*user model 'xy': its files would be those of model 'x_y'" gate clash2_gate.json
printf '/* brdfbench-model\n * name: x_y\n */\nREAL x_y(REAL c, REAL n)\n{\n    return c;\n}\n' >x_y.cl
t 2 "^brdfbench accuracy: --model xy: user model 'xy': its files would be those of model 'x_y'" accuracy --model-file x_y.cl --model 'xy=c' --out run
printf '/* brdfbench-model\n * name: fq2_error\n */\nREAL fq2_error(REAL c, REAL n)\n{\n    return c;\n}\n' >fq2_error.cl
t 2 "^brdfbench render: .*fq2_error.cl: user model 'fq2_error': its files would be those of model 'fq2' \(render's fq2_error.png\)" render --model-file fq2_error.cl --out run
printf '{"gates":[{"model":"fq_2","expression":"c*c","metric":"whole.max_abs","max":1}]}' >clash_gate.json
t 2 "^brdfbench gate: clash_gate.json:1:[0-9]+: gate 1: .*user model 'fq_2': its files would be those of model 'fq2'" gate clash_gate.json

# A model that is NaN everywhere, against a run where the same model was finite: named.
"$BIN" accuracy --model 'um=c*c' --n-max 20 --samples 64 --out ua --quiet >/dev/null 2>&1
"$BIN" accuracy --model 'um=c*NAN' --n-max 20 --samples 64 --out ub --quiet >/dev/null 2>&1
t 1 "multi:^ub: accuracy um \| n 2\.\.20 .* epicentre\.max_rel: no finite error values" compare ua ub --fail-if-less-accurate --out cmpo --quiet

# A compile error's first line is the compiler's own FILE:LINE:COL line.
"$BIN" accuracy --model-file "$F/bad_syntax.cl" --n-max 4 --samples 16 --out run >/dev/null 2>"$T/err"
# (a build that takes over a second prints its progress first, "brdfbench: building ...: 1 s so far
# (deadline ...)", as every slow build does: those lines are not the error's)
grep -vE '^brdfbench: building .*: [0-9]+ s so far \(deadline' "$T/err" | head -n 1 |
    grep -qE "^[^ ]*bad_syntax.cl:6:[0-9]+: error: expected ';'" && pass=$((pass + 1)) ||
    { fail=$((fail + 1)); echo "FAIL: a compile error starts with: $(head -n 1 "$T/err")" >&2; }

# The rows of each area in files of their own (tests/bad_inputs/*.sh, sourced in name order):
# they use t, WHAT and the fixtures above, and write only into this test's folder.
first_area_row=$((row + 1))
for rows_file in "$SRC"/tests/bad_inputs/*.sh; do
    [ -f "$rows_file" ] || continue
    # shellcheck source=/dev/null
    . "$rows_file"
done

# One more check: no refused run above wrote its output folder.
[ ! -e "$T/run" ] && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL: a refused run wrote $T/run" >&2; }

if [ -n "${BAD_INPUTS_MD:-}" ]; then
    {
        echo "# Bad inputs"
        echo
        echo "Every row is a case of tests/test_cli_errors.sh: the command (in brackets, what the small files the"
        echo "test made for it hold, or how it changed a copy of a run folder), the exit code it gave and the first"
        echo "matching line of stderr (each asserted: exit code and message). Exit 2 is bad input, 3 a runtime"
        echo "or output error, 77 no OpenCL device (docs/architecture.md). Rows 155 on are the hostile inputs of"
        echo "issue 23: result files fed back, names that become file names, model texts, limits, environments;"
        echo "rows 341 on its rest: rows a run lost (compare exits 1 naming them), figures and labels compare"
        echo "refuses, user models whose files would be another model's; rows $first_area_row on, those of"
        echo "tests/bad_inputs/*.sh, one file per area (the .brdf corpus, exact corpus files, full BRDFs,"
        echo "hardening, the store and history, shader code)."
        echo "Made with \`BAD_INPUTS_MD=docs/bad-inputs.md bash tests/test_cli_errors.sh\`"
        echo "(BRDFBENCH and SRC_DIR set as ctest sets them): $row cases, one check that no refused run"
        echo "wrote an output folder and one that a compile error's first line is FILE:LINE:COL; $pass passed, $fail failed."
        echo
        echo "| # | command | exit | message | result |"
        echo "|---|---|---|---|---|"
        printf '%s' "$md"
        cat <<'EOT'

## What a row cannot show

Some hostile inputs are about what must *not* happen: a file replaced outside the run folder,
an earlier run lost, a hang. tests/test_hostile.sh checks those effects (each check failed on
the binary before its fix, issue 23); the rows above with the same inputs check their exit
code and message.

- A symlink inside a run folder (`heatmap_fq2.png -> /tmp/victim`): `heatmap` and `plot`
  replace the link by the picture; the link's target is unchanged. Outputs named on the command
  line still write through a link (tests/test_outputs.sh).
- `plots.json` naming a data file of the run (`accuracy.json`, `plots.json`, `report.md`,
  `field_fq2.json`, `x.PNG.json`) or a path: exit 2, and no file of the run folder changes.
- A `y_range` of `[1e-300, 2e-300]`, `[1, 1 + 1e-15]` or `[1e-320, 1e-310]`: exit 2 within
  seconds; a point at 1e300 inside a valid range is clipped, not dashed along 1e300 pixels.
- A FIFO as `accuracy.json` (compare, `gate --baseline`), `plots.json`, `field_*.json`,
  `brdf_models.h` of `--kernel-dir` or a model file: exit 2 at once, no wait for a writer.
- `--teapot-file /dev/zero`, a folder, or a 300 MB file: exit 2 before anything is read.
- The wrapper `brdf_user_eval` in an expression (also in a gates file), a model file whose
  function calls itself: exit 2 before the OpenCL compiler sees it (it crashed with SIGSEGV).
- A gates file naming a model file outside its folder (`../x.cl`, an absolute path, a link
  out): exit 2 before the file is read or compiled; `--allow-outside-model-files` runs it.
- A host reference that never returns: a progress line after a second, then exit 3 at the
  deadline with the run's folder removed.
- `all --out mix` over a complete earlier run, failing (a model that loops only in float, exit
  3), stopped by SIGTERM or SIGINT: `mix` is file for file as it was, and no staging folder is
  left; a complete run replaces `mix` as a whole (a stale file of the earlier run is gone);
  `all --results-root rs` stopped: no half run in `rs`.
- `all --out` a folder of other files, or the working folder: exit 2, the folder untouched.
- `results/latest` that is a folder or a file: exit 3 before the run, and the file is kept.
- A hard link to a model file given twice is one model; `--json nowhere/x.json` fails before
  the device is opened; SIGTERM of `accuracy --out a/b/D` leaves no folder it made.
- `accuracy --device all --json -`: one document on standard output (the rows of every device),
  no results folder.
- `ulimit -v 200000` or `400000`: exit 77 or 3 with a line that names the limit, not abort()
  on an uncaught std::bad_alloc (exit 134).
- A model that is NaN everywhere (`--model 'nanm=c*NAN'`): failed in accuracy.json, in
  throughput.json (the row's status failed with the reason, no rate, no share of the peak),
  in render.json (max |error| null, status nonfinite, not 0), in frontier.json (null figures,
  not -1; status failed, off the front) and in report.md; a gate on it fails.
- An accuracy-only compare draws its own compare.png (its error rows as ratios to the baseline's)
  in place of one an earlier compare left;
  `gate --baseline` says why an entry was not used (failed, no number, another n step).
EOT
    } >"$BAD_INPUTS_MD.tmp" && mv "$BAD_INPUTS_MD.tmp" "$BAD_INPUTS_MD"
fi
echo "$row cases + 2 checks: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
