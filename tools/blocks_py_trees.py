"""The py_trees side of tools/blocks_vs_lua.sh: N behaviours under one Parallel node
(SuccessOnAll), each the counting block of issue 14: it counts once a tick and stays
RUNNING until it reaches 100. Prints: py_trees N ns_per_step bytes_per_behaviour
(tracemalloc's growth over the tree's creation and first two ticks, over N).

    python3 tools/blocks_py_trees.py N TICKS
"""

import sys
import time
import tracemalloc

import py_trees


class Block(py_trees.behaviour.Behaviour):
    def __init__(self, name):
        super().__init__(name)
        self.c = 0

    def update(self):
        if self.c < 100:
            self.c += 1
            return py_trees.common.Status.RUNNING
        return py_trees.common.Status.SUCCESS


def main():
    n, ticks = int(sys.argv[1]), int(sys.argv[2])
    tracemalloc.start()
    before = tracemalloc.get_traced_memory()[0]
    root = py_trees.composites.Parallel(
        name="blocks",
        policy=py_trees.common.ParallelPolicy.SuccessOnAll(),
        children=[Block(f"c{i}") for i in range(n)],
    )
    root.tick_once()
    root.tick_once()
    size = (tracemalloc.get_traced_memory()[0] - before) / n
    tracemalloc.stop()
    start = time.process_time()
    for _ in range(ticks):
        root.tick_once()
    elapsed = time.process_time() - start
    print(f"py_trees {n} {elapsed * 1e9 / (ticks * n):.1f} {size:.0f}")


main()
