#!/usr/bin/env bash
# test_machine_readable.sh - one --samples range for every command (or the reason for a smaller
# one, in its --help), and --json - (the document alone on standard output) on every command
# that writes a document.
set -u
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"
brdf_test_init
cd "$T" || exit 1

# 1. --samples: every command that takes it accepts [16, 4194304] (the accuracy sweep's
#    ACC_MAX_SAMPLES, 2^22), or its --help entry states why it takes less ("since ...").
COMMANDS=$("$BIN" --help | awk '/^  [a-z]/ { print $1 }' | tr '\n' ' ')
for c in $COMMANDS; do
    "$BIN" "$c" --help >"$T/help_$c" 2>&1
    # the entry with its continuation lines (indented 21 columns) joined
    entry=$(python3 -c '
import re, sys
lines, out = open(sys.argv[1]).read().split("\n"), []
for i, l in enumerate(lines):
    if l.startswith("  --samples "):
        out = [l] + [m for m in __import__("itertools").takewhile(lambda m: m.startswith(" " * 21), lines[i + 1:])]
print(" ".join(x.strip() for x in out))' "$T/help_$c")
    [ -n "$entry" ] || continue
    hi=$(printf '%s' "$entry" | grep -oE 'in \[16, [0-9]+\]' | grep -oE '[0-9]+\]' | tr -d ']')
    if [ "$hi" = 4194304 ] || printf '%s' "$entry" | grep -qE 'since|because'; then ok
    else bad "$c --samples: maximum $hi differs from 4194304 with no reason: $entry"; fi
done

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
