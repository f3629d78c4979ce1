#!/bin/sh
# Builds every task in examples/ (and the experiment tasks) for each robot and skill
# directory it checks with, and writes `ilmrc disasm` of each into OUT_DIR, one file per
# combination. Run it with two binaries and `diff -r` the directories to show that a
# change to the compiler leaves the bytecode as it was:
#
#   ILMRC=/tmp/old/ilmrc tools/disasm_examples.sh /tmp/disasm-old
#   ILMRC=./target/debug/ilmrc tools/disasm_examples.sh /tmp/disasm-new
#   diff -r /tmp/disasm-old /tmp/disasm-new
set -eu
ILMRC=${ILMRC:-./target/debug/ilmrc}
out=${1:?usage: tools/disasm_examples.sh OUT_DIR}
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for task in examples/*.ilmr experiments/tasks/*.ilmr; do
    for robot in moro workpartner; do
        for skills in examples/skills examples/skills_moro; do
            name=$(echo "$task-$robot-$skills" | tr '/' '_')
            if "$ILMRC" build --robot "$robot" --skills "$skills" -o "$tmp/m.ilmb" "$task" >/dev/null 2>&1; then
                "$ILMRC" disasm "$tmp/m.ilmb" >"$out/$name.txt"
            else
                echo "rejected" >"$out/$name.txt"
            fi
        done
    done
done
ls "$out" | wc -l | xargs echo "listings written:"
grep -L '^rejected$' "$out"/* | wc -l | xargs echo "of which built:"
