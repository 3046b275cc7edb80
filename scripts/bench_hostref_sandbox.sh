#!/usr/bin/env bash
# bench_hostref_sandbox.sh - what the host reference's sandbox (host/core/hostjit.c) costs.
#
# 1. per value: build/tests/bench_hostjit calls one compiled model (quad.cl's formula) in this
#    process (as before the sandbox), through the sandbox one value per request (as the
#    accuracy sweep's Brent searches ask) and in batches of 512; medians of ROUNDS rounds,
#    interleaved, and the ratios.
# 2. a whole run: scripts/bench_usermodels.sh (a user model against the same formula as a
#    built-in, accuracy over n in [2, 1000] and a gate over [2, 200]) with this build, and with
#    OLD_BRDFBENCH too when it names a build from before the sandbox (for the same ratio then).
# A benchmark, not a test: it asserts nothing. Figures depend on the machine's load: both
# processes must be on a core at once for a one-value request to cost a cache line's trip.
#
#   scripts/bench_hostref_sandbox.sh [BUILD_DIR] [ROUNDS]      (defaults: build, 5)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
rounds=${2:-5}
[ -x "$build/tests/bench_hostjit" ] || { echo "bench_hostref_sandbox: build $build/tests/bench_hostjit first" >&2; exit 2; }
echo "== per value"
SRC_DIR=$PWD "$build/tests/bench_hostjit" "$rounds" 200000
echo "== a run with a user model (this build: $build/brdfbench)"
BENCH_ONLY="accuracy gate" scripts/bench_usermodels.sh "$build/brdfbench" "$rounds"
if [ -n "${OLD_BRDFBENCH:-}" ]; then
  echo "== the same with the build before the sandbox ($OLD_BRDFBENCH)"
  BENCH_ONLY="accuracy gate" scripts/bench_usermodels.sh "$OLD_BRDFBENCH" "$rounds"
fi
