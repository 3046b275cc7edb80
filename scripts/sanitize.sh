#!/usr/bin/env bash
# sanitize.sh - the test suite built with AddressSanitizer and UndefinedBehaviorSanitizer
# (cmake -DBRDF_SANITIZE=ON, into build-asan/) and run by ctest. CI runs it after
# scripts/test.sh; it exits non-zero on any test failure or sanitizer report.
#
# PoCL under ASan: the CPU driver runs as is (no protect_shadow_gap or other workaround is
# needed with Debian 12's PoCL 3.1 and LLVM 15), but PoCL, LLVM and the ICD loader keep
# allocations until exit, which LeakSanitizer would report: those libraries' leaks are
# suppressed, while leaks whose stack lies in brdfbench's own code are still reported.
# Every sanitizer report turns the exit code into 86, so a test that expects a particular
# exit code (0, 1, 2, 3 or 77) fails on it.
set -euo pipefail
cd "$(dirname "$0")/.."
B=build-asan
cmake -S . -B "$B" -DBRDF_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$B" -j2

# The binary must carry the instrumentation, or this run would prove nothing.
symbols=$(nm "$B/brdfbench" 2>/dev/null || true)
if ! grep -q '__asan_init' <<<"$symbols" || ! grep -q '__ubsan_handle' <<<"$symbols"; then
    echo "sanitize.sh: $B/brdfbench is not built with ASan and UBSan" >&2
    exit 1
fi

supp="$PWD/$B/lsan-suppressions.txt"
cat >"$supp" <<'EOF'
# Allocations that the OpenCL driver stack keeps until the process exits.
leak:libpocl.so
leak:libLLVM
leak:libclang-cpp
leak:libOpenCL.so
leak:libhwloc
# Mesa's OpenCL drivers (rusticl and Clover, mesa-opencl-icd) are loaded by the ICD loader in
# every process on a machine that has them, and keep allocations of their own too.
leak:libRusticlOpenCL
leak:libMesaOpenCL
leak:libgallium
# The drawing module's OpenCV and what it loads (GDAL among them), opened with dlopen when a
# command first draws, keep allocations in their thread storage until exit; with use_tls=0
# below (why: there) those read as leaks, as do the loader's own thread-storage vectors.
leak:libgdal
leak:libopencv_
leak:libtbb
leak:libgomp
leak:_dl_resize_dtv
leak:_dl_allocate_tls
# the C library's dlerror text, held in thread storage (the ICD loader's failed dlopen)
leak:_dlerror_run
leak:_dl_exception_create_format
EOF
# The suite runs against PoCL alone here. Mesa's OpenCL drivers (mesa-opencl-icd, which CI
# installs for test_rusticl) are otherwise loaded into every process by the ICD loader; they
# load and unload their gallium pipe drivers, and an allocation made from an unloaded library is
# reported as "<unknown module>", which no suppression can name. The tests of other drivers are
# labelled no_sanitizer and run in scripts/test.sh.
vendors="$PWD/$B/icd-vendors"
mkdir -p "$vendors"
rm -f "$vendors"/*.icd
if [ -f /etc/OpenCL/vendors/pocl.icd ]; then
    cp /etc/OpenCL/vendors/pocl.icd "$vendors/"
    export OCL_ICD_VENDORS="$vendors"
fi
export ASAN_OPTIONS="exitcode=86:detect_leaks=1"
# use_tls=0: LeakSanitizer's stop-the-world tracer crashes (signal 11, "Tracer caught signal 11",
# every time, in `measured`) walking the dynamic thread storage of the libraries that the drawing
# module brings in with dlopen; brdfbench's own code keeps no heap pointer in thread storage.
export LSAN_OPTIONS="exitcode=86:suppressions=$supp:print_suppressions=0:use_tls=0"
export UBSAN_OPTIONS="exitcode=86:halt_on_error=1:print_stacktrace=1"

# The kernels the suite builds are the same in both builds: start from the PoCL kernel cache
# that scripts/test.sh's run filled (build/pocl-cache, the tests' POCL_CACHE_DIR), so the
# sanitizer run does not compile every program again.
if [ -d build/pocl-cache ] && [ ! -e "$B/pocl-cache" ]; then
    cp -a build/pocl-cache "$B/pocl-cache"
fi

cd "$B"
# LeakSanitizer's own stop-the-world tracer now and then crashes at a process's exit while
# other threads (PoCL's workers) wind down: "Tracer caught signal 11 ... LeakSanitizer has
# encountered a fatal error" is the tool failing, not a leak or an error found (a known flake:
# google/sanitizers issue 1353). A run whose failures came with that message reruns its failed
# tests once; any other failure, or a failure again, fails the run.
log=$(mktemp)
trap 'rm -f "$log"' EXIT
set +e
# The tests labelled no_sanitizer (tests/CMakeLists.txt says why each) run in scripts/test.sh
# only. Besides the drivers', packaging and timing tests listed there, four are left out so that
# CI's two passes fit its time on a 2-core machine; what each checks is not memory safety of code
# that no other test runs under the sanitizers:
#   test_deadline         most of its time is the deadlines it waits out (sleeping); the launch
#                         watchdog and the stop paths it reaches run in every device test here,
#                         and a stopped run's tidy-up in test_hostile and test_atomic;
#   test_throughput_cli   timed runs of the throughput engine; its host code (the runner, the
#                         writers) runs here in test_throughput and test_runner;
#   test_ln_unit          the kernels' log against the C library's, every 61st float in [2^-24, 1]: device
#                         arithmetic, with a plain loop on the host;
#   test_accuracy_pictures  accuracy --pictures and plot of user models: the drawing code runs
#                         here in test_draw, test_redraw and test_draw_module (plot), accuracy's
#                         in test_accuracy and test_cli_accuracy, user models' in test_usermodel.
# Every unit and device C test and the bad-input and hostile-input tables (test_cli_errors,
# test_hostile) run under the sanitizers.
ctest --output-on-failure -j3 --timeout 900 -LE no_sanitizer   # -j3: as scripts/test.sh 2>&1 | tee "$log"
rc=${PIPESTATUS[0]}
set -e
if [ "$rc" -ne 0 ] && grep -q "LeakSanitizer has encountered a fatal error" "$log"; then
    echo "sanitize.sh: LeakSanitizer's tracer crashed (not a finding); the failed tests once more:" >&2
    ctest --output-on-failure --rerun-failed --timeout 900 && rc=0 || rc=$?
fi
exit "$rc"
