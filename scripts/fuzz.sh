#!/usr/bin/env bash
# fuzz.sh [SECONDS] - bounded libFuzzer runs of the input parsers: the gates file
# (tests/fuzz/fuzz_gates.c) and the user-model file and expression (tests/fuzz/
# fuzz_modelfile.c), each for SECONDS (default 60), with ASan and UBSan. Not part of CI.
#
# The library is built with Debian's clang into build-fuzz/ (-fsanitize=fuzzer-no-link), each
# target is linked with -fsanitize=fuzzer. The corpus starts from the project's own gates and
# model files and grows in build-fuzz/corpus-*/; a crash leaves its input in
# build-fuzz/crash-* and makes this script exit non-zero.
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:-60}
case "$secs" in ''|*[!0-9]*) echo "usage: scripts/fuzz.sh [SECONDS]" >&2; exit 2 ;; esac
command -v clang >/dev/null || { echo "fuzz.sh: clang is missing (apt-get install clang libclang-rt-14-dev)" >&2; exit 2; }

B=build-fuzz
san="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g"
CC=clang CXX=clang++ cmake -S . -B "$B" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_FLAGS="$san -fsanitize=fuzzer-no-link" -DCMAKE_CXX_FLAGS="$san -fsanitize=fuzzer-no-link" >/dev/null
cmake --build "$B" -j2 --target brdfcore

libs="$(pkg-config --libs opencv4 gsl jansson) -lOpenCL -ltcc -ldl -lm -lpthread"
export ASAN_OPTIONS="detect_leaks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
status=0
for target in gates modelfile; do
    # Linked by clang++: the library holds C++ (host/draw/draw.cpp) and UBSan's C++ runtime.
    # shellcheck disable=SC2086
    clang $san -fsanitize=fuzzer -DCL_TARGET_OPENCL_VERSION=120 -I host/cli $(for d in host/measure host/measure/*/ host/results host/results/*/; do printf -- "-I %s " "$d"; done) -I host/core -I host/core/shader -I host/output -I kernels \
        -c "tests/fuzz/fuzz_$target.c" -o "$B/fuzz_$target.o"
    # shellcheck disable=SC2086
    clang++ $san -fsanitize=fuzzer "$B/fuzz_$target.o" "$B/libbrdfcore.a" $libs -o "$B/fuzz_$target"
    corpus="$B/corpus-$target"
    mkdir -p "$corpus"
    if [ "$target" = gates ]; then seeds=(tests/gates/*.json); else seeds=(tests/test_usermodel_files/*.cl); fi
    cp -n "${seeds[@]}" "$corpus/" 2>/dev/null || true
    echo "fuzz.sh: $target for ${secs} s" >&2
    # stdin is /dev/null: a model file named /dev/stdin in a gates file reads an empty file.
    if ! (cd "$B" && "./fuzz_$target" -max_total_time="$secs" -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
            -dict="../tests/fuzz/$target.dict" -artifact_prefix="./crash-$target-" "corpus-$target" </dev/null); then
        echo "fuzz.sh: $target found a failing input (see $B/crash-$target-*)" >&2
        status=1
    fi
done
exit $status
