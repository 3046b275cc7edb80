#!/usr/bin/env bash
# test_install.sh - cmake --install and the Debian package: the installed program runs (list),
# its man pages and shell completions are those the program writes now from its flag tables
# (regenerated here and compared), each man page lists exactly the flags of the command's
# --help, `brdfbench help COMMAND` is the command's --help, every --help shows an example, the
# bash completion completes commands and flags, and cpack -G DEB builds a package holding the
# same files, whose extracted binary runs; both install the drawing module, through which the
# installed binaries draw.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
B=${BUILD_DIR:?BUILD_DIR must name the build folder}
CMAKE=${CMAKE_COMMAND:-cmake}
CPACK=${CPACK_COMMAND:-cpack}
P=$T/prefix

# 1. Install into a prefix and run the installed binary.
"$CMAKE" --install "$B" --prefix "$P" >"$T/install.log" 2>&1 && ok || bad "cmake --install: $(tail -3 "$T/install.log")"
"$P/bin/brdfbench" list >"$T/list.out" 2>"$T/list.err"
rc=$?
{ [ $rc -eq 0 ] || [ $rc -eq 77 ]; } && grep -q "fq2" "$T/list.out" && ok || bad "installed brdfbench list: exit $rc: $(head -3 "$T/list.err")"
commands=$("$BIN" help | awk '/^commands:/ {on = 1; next} on {print $1}')
[ "$(echo $commands | wc -w)" -ge 14 ] && ok || bad "brdfbench help lists too few commands: $commands"
for f in brdfbench.1 $(for c in $commands; do echo "brdfbench-$c.1"; done); do
    [ -s "$P/share/man/man1/$f" ] || { bad "not installed: share/man/man1/$f"; continue; }
    ok
done
for f in share/bash-completion/completions/brdfbench share/zsh/vendor-completions/_brdfbench \
         share/doc/brdfbench/README.md share/doc/brdfbench/user-models.md; do
    [ -s "$P/$f" ] && ok || bad "not installed: $f"
done

# 1b. The drawing module is installed (LIBDIR/brdfbench) and the installed binary draws through
# it: plot of the run folder that test_cli_errors reads too (the fixture brdf_runs).
installed_draws() {   # BINARY LABEL
    [ -n "${BRDF_RUNS:-}" ] && [ -f "$BRDF_RUNS/done" ] || { echo "no fixture run (BRDF_RUNS): $2 draws unchecked"; return; }
    rm -rf "$T/draw" && cp -r "$BRDF_RUNS/R0" "$T/draw"
    "$1" plot "$T/draw" >"$T/plot.out" 2>"$T/plot.err"
    local rc=$?
    [ $rc -eq 0 ] && grep -q '\.png$' "$T/plot.out" && ok || bad "$2 plot: exit $rc: $(head -3 "$T/plot.err")"
}
find "$P" -name libbrdfbench-draw.so -path '*/brdfbench/*' | grep -q . && ok || bad "the drawing module is not installed under $P"
installed_draws "$P/bin/brdfbench" "installed brdfbench"

# 2. Regenerated now, they are the installed files, byte for byte.
mkdir -p "$T/regen/man1"
"$BIN" help --man-dir "$T/regen/man1" && ok || bad "help --man-dir failed"
diff -r "$T/regen/man1" "$P/share/man/man1" >"$T/diff" && ok || bad "installed man pages differ from the flag tables: $(head -20 "$T/diff")"
"$BIN" help --completion bash | cmp -s - "$P/share/bash-completion/completions/brdfbench" && ok || bad "bash completion differs"
"$BIN" help --completion zsh | cmp -s - "$P/share/zsh/vendor-completions/_brdfbench" && ok || bad "zsh completion differs"

# 3. Each man page's options are the command's --help flags; help COMMAND is COMMAND --help; an example each.
for c in $commands; do
    "$BIN" "$c" --help >"$T/h" 2>&1
    help_flags=$(grep -oE '^  --?[A-Za-z0-9][A-Za-z0-9-]*' "$T/h" | tr -d ' ' | sort -u)
    man_flags=$(grep -A1 '^\.TP' "$P/share/man/man1/brdfbench-$c.1" | grep '^\.B ' \
                | sed 's/^\.B //; s/\\f.*//; s/ .*//; s/\\-/-/g' | sort -u)
    [ -n "$help_flags" ] && [ "$help_flags" = "$man_flags" ] && ok || bad "$c: man page flags differ from --help:
$(diff <(echo "$help_flags") <(echo "$man_flags"))"
    "$BIN" help "$c" | cmp -s - "$T/h" && ok || bad "brdfbench help $c is not brdfbench $c --help"
    grep -A1 '^example:' "$T/h" | grep -q "^  brdfbench $c" && ok || bad "$c --help has no example"
done
expect 2 "unknown command 'nosuch'" help nosuch

# 4. The bash completion completes a command and a command's flags.
comp() {
    bash -c '. "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _brdfbench; echo "${COMPREPLY[*]}"' \
        _ "$P/share/bash-completion/completions/brdfbench" "$@"
}
[ "$(comp brdfbench accu)" = "accuracy" ] && ok || bad "bash completion of 'accu': '$(comp brdfbench accu)'"
[ "$(comp brdfbench accuracy --n-m)" = "--n-min --n-max" ] && ok || bad "bash completion of '--n-m': '$(comp brdfbench accuracy --n-m)'"
[ "$(comp brdfbench help thr)" = "throughput" ] && ok || bad "bash completion of 'help thr': '$(comp brdfbench help thr)'"

# 5. The Debian package: the same files, and its binary runs.
(cd "$B" && "$CPACK" -G DEB -B "$T/pkg" >"$T/cpack.log" 2>&1) && ok || bad "cpack -G DEB: $(tail -5 "$T/cpack.log")"
deb=$(ls "$T"/pkg/*.deb 2>/dev/null | head -1)
if [ -n "$deb" ]; then
    dpkg-deb -c "$deb" >"$T/contents"
    grep -qE " ./usr/lib/([^ ]*/)?brdfbench/libbrdfbench-draw.so\$" "$T/contents" && ok || bad "the package lacks the drawing module"
    dpkg-deb -f "$deb" Depends | grep -q "libopencv-imgcodecs" && ok || bad "the package does not depend on OpenCV (its drawing module's)"
    for f in ./usr/bin/brdfbench ./usr/share/man/man1/brdfbench-accuracy.1 \
             ./usr/share/bash-completion/completions/brdfbench ./usr/share/doc/brdfbench/README.md; do
        grep -q " $f\$" "$T/contents" && ok || bad "the package lacks $f"
    done
    dpkg-deb -f "$deb" Depends | grep -q "libopencl" && ok || bad "the package does not depend on an OpenCL loader"
    dpkg-deb -x "$deb" "$T/x"
    "$T/x/usr/bin/brdfbench" list >"$T/list2.out" 2>&1
    rc=$?
    { [ $rc -eq 0 ] || [ $rc -eq 77 ]; } && grep -q "fq2" "$T/list2.out" && ok || bad "the package's brdfbench list: exit $rc"
    installed_draws "$T/x/usr/bin/brdfbench" "the package's brdfbench"
else
    bad "no .deb in $T/pkg"
fi

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
