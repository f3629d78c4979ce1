#!/bin/sh
# The VM's general path side by side with Lua 5.4 coroutines and py_trees (issue 14,
# item 3): the same workload on each, N blocks each counting to 100 one step a tick
# (ILMR: `cN=0` / `while(cN<100)` / `cN=cN+1` / `wait(0.01)` / `endwhile`, compiled by
# the real compiler, `--robot none`'s VM in process; Lua: a coroutine per block resumed
# round-robin; py_trees: a behaviour per block under one Parallel), at 10,000, 100,000
# and 1,000,000 blocks. Prints one table: ns per block step and bytes per task for
# each side, and ILMR's ratio to Lua. Figures in docs/performance.md.
#
#   apt-get install lua5.4; pip install py_trees   # py_trees is optional
#   tools/blocks_vs_lua.sh [TICKS]                  # default 50 timed ticks
#
# Each side runs alone, one after the other, one thread each. ns per step: the time of
# the timed ticks (ILMR's wall clock, Lua's os.clock, Python's process_time) over
# ticks x blocks, the fastest of RUNS runs (default 3). Bytes per task:
# ILMR the VM's run-time state (`Vm::footprint`), Lua the collector's count, py_trees
# tracemalloc; each over the blocks, the program's code not counted.
set -eu
TICKS=${1:-50}
RUNS=${RUNS:-3}
SIZES=${SIZES:-"10000 100000 1000000"}
here=$(dirname "$0")
cargo build -q --release -p ilmr-compiler --example blocks_run
ilmr=./target/release/examples/blocks_run
lua=$(command -v lua5.4 || true)
py=
if python3 -c 'import py_trees' 2>/dev/null; then py=python3; fi

# fastest CMD...: the run of RUNS with the least ns per step (field 3).
fastest() {
    best=
    for _ in $(seq "$RUNS"); do
        line=$("$@")
        if [ -z "$best" ] || [ "$(echo "$line" | awk '{print $3}' | cut -d. -f1)" -lt \
            "$(echo "$best" | awk '{print $3}' | cut -d. -f1)" ]; then
            best=$line
        fi
    done
    echo "$best"
}

echo "| blocks | ILMR ns/step | Lua 5.4 ns/step | py_trees ns/step | Lua / ILMR | ILMR bytes/task | Lua bytes/task | py_trees bytes/task |"
echo "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for n in $SIZES; do
    # Its fifth field, the wall time, is left out of the table: the figures compared
    # are CPU time, the clock Lua's `os.clock` reads.
    i=$(fastest "$ilmr" "$n" "$TICKS" | cut -d' ' -f1-4)
    if [ -n "$lua" ]; then l=$(fastest "$lua" "$here/blocks.lua" "$n" "$TICKS"); else l="lua - n/a n/a"; fi
    # py_trees takes microseconds a step: fewer ticks, and once, at a million.
    if [ -z "$py" ]; then
        p="py_trees - not-installed -"
    elif [ "$n" -ge 1000000 ]; then
        p=$("$py" "$here/blocks_py_trees.py" "$n" 2)
    else
        p=$(RUNS=1 fastest "$py" "$here/blocks_py_trees.py" "$n" 5)
    fi
    ratio=$(echo "$i $l" | awk '{ if ($7 + 0 > 0) printf "%.2f", $7 / $3; else print "-" }')
    echo "$i $l $p $ratio" | awk '{printf "| %s | %s | %s | %s | %s | %s | %s | %s |\n", $2, $3, $7, $11, $13, $4, $8, $12}'
done
