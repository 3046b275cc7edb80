#!/usr/bin/env bash
# fixture_runs.sh [DIR] - the two runs that tests/test_cli_errors.sh and tests/test_hostile.sh
# both read, made once: DIR/R0, a run folder of `brdfbench all --quick --models fq2`, and
# DIR/base, an accuracy run of fq2 and cq2 (n up to 50, 256 samples). The tests copy them and
# never change them in place.
#
# ctest runs it as the setup of the fixture brdf_runs (tests/CMakeLists.txt), with DIR from
# $BRDF_RUNS; a test run by hand without that fixture calls it with its own folder. DIR/done
# is written last, once both runs succeeded; a test finds the runs ready only when it is there.
# Exits 77 (skipped) without an OpenCL device, 1 when a run fails.
set -u
BIN=${BRDFBENCH:?BRDFBENCH must name the brdfbench binary}
DIR=${1:-${BRDF_RUNS:?BRDF_RUNS must name the folder of the shared runs}}
mkdir -p "$DIR" && cd "$DIR" || exit 1
rm -rf R0 base done
# The same commands, in the same words, as the tests ran them in their own folders.
"$BIN" all --quick --models fq2 --out R0 --quiet >all.out 2>all.err
rc=$?
if [ $rc -eq 77 ]; then echo "no OpenCL device"; echo "0 passed, 0 failed, 1 skipped"; exit 77; fi
[ $rc -eq 0 ] || { echo "FAIL: all --quick --models fq2 --out R0: exit $rc: $(head -c 600 all.err)"; exit 1; }
"$BIN" accuracy --models fq2,cq2 --n-max 50 --samples 256 --out base --quiet >acc.out 2>acc.err
rc=$?
[ $rc -eq 0 ] || { echo "FAIL: accuracy --out base: exit $rc: $(head -c 600 acc.err)"; exit 1; }
rm -f all.out all.err acc.out acc.err
touch done
echo "2 passed, 0 failed"
