#!/usr/bin/env bash
# test_outputs.sh - an output path is written through, never replaced, when it is not a
# regular file (docs/architecture.md, habit 11): standard output as `-` or /dev/stdout, a FIFO, a
# character device, a symlink to a file elsewhere (the link stays a link, its target gets the
# text, replaced atomically in the target's own folder). The gate's reports are the outputs
# named on the command line, so they are the ones tried here.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
cd "$T" || exit 1
printf '{"gates": [{"model": "fq2", "metric": "epicentre.max_rel", "n_max": 20, "samples": 64, "max": 1}]}\n' >g.json

# /dev/stdout redirected to a file: the JSON lands in the file, after the gate lines, and
# /dev/stdout is still the link it was.
"$BIN" gate g.json --json /dev/stdout >log 2>err
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] && ok || bad "--json /dev/stdout: exit $rc: $(head -c 400 err)"
grep -q '^PASS ' log && grep -q '"schema": "brdfbench.gate/1"' log && ok \
    || bad "--json /dev/stdout: log lacks the gate line or the JSON: $(head -c 300 log)"
[ "$(sed -n '/^{/,$p' log | python3 -c 'import json,sys; print(json.load(sys.stdin)["schema"])')" = brdfbench.gate/1 ] \
    && ok || bad "--json /dev/stdout: the JSON in log does not parse"
[ -L /dev/stdout ] && ok || bad "/dev/stdout is no longer a symlink"
# `-` is standard output too; through a pipe.
"$BIN" gate g.json --quiet --junit - 2>err | grep -c '<testcase ' >count
[ "$(cat count)" = 1 ] && ok || bad "--junit -: $(cat count) testcases through the pipe: $(head -c 300 err)"

# A symlink in the project's folder to a file elsewhere: still a link afterwards, the target
# holds the report, and neither folder holds a temporary file.
mkdir proj elsewhere
echo old >elsewhere/report.json
ln -s ../elsewhere/report.json proj/report.json
"$BIN" gate g.json --quiet --json proj/report.json >/dev/null 2>err
[ $? -eq 0 ] && ok || bad "--json symlink: $(head -c 300 err)"
[ -L proj/report.json ] && [ "$(readlink proj/report.json)" = ../elsewhere/report.json ] && ok \
    || bad "--json symlink: the link was replaced"
grep -q '"schema": "brdfbench.gate/1"' elsewhere/report.json && ok || bad "--json symlink: the target lacks the report"
[ "$(ls -A proj elsewhere | grep -c tmp)" = 0 ] && ok || bad "temporary files left: $(ls -A proj elsewhere)"
# A chain of two links, the second one absolute.
ln -s "$T/elsewhere/deep.xml" elsewhere/mid.xml
ln -s ../elsewhere/mid.xml proj/chain.xml
"$BIN" gate g.json --quiet --junit proj/chain.xml >/dev/null 2>err
[ -L proj/chain.xml ] && [ -L elsewhere/mid.xml ] && grep -q '<testsuite' elsewhere/deep.xml && ok \
    || bad "--junit through two links: $(ls -l proj elsewhere) $(head -c 300 err)"

# A FIFO read by a background cat.
mkfifo pipe.xml
cat pipe.xml >from_pipe.xml &
reader=$!
"$BIN" gate g.json --quiet --junit pipe.xml >/dev/null 2>err
rc=$?
wait "$reader"
[ $rc -eq 0 ] && [ -p pipe.xml ] && grep -q '<testcase ' from_pipe.xml && ok \
    || bad "--junit FIFO: exit $rc, $(ls -l pipe.xml), read: $(head -c 200 from_pipe.xml) $(head -c 300 err)"

# A character device stays one.
"$BIN" gate g.json --quiet --json /dev/null >/dev/null 2>err
[ $? -eq 0 ] && [ -c /dev/null ] && ok || bad "--json /dev/null: $(head -c 300 err)"

# A regular file is replaced atomically: a new inode, the old one untouched (a hard link
# to it keeps the old text).
echo old >plain.json
ln plain.json plain-old.json
"$BIN" gate g.json --quiet --json plain.json >/dev/null 2>err
[ "$(cat plain-old.json)" = old ] && grep -q '"schema": "brdfbench.gate/1"' plain.json && ok \
    || bad "--json regular file: not replaced by rename"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
