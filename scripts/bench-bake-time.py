"""Whole-process bake times of chamfer binaries on one mesh, interleaved round by round so the
machine's drift falls on every binary alike; prints medians and ratios against the first.

    python3 scripts/bench-bake-time.py MESH ROUNDS NAME=COMMAND... (each COMMAND gets `bake MESH -o OUT`)
"""
import os
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

mesh, rounds, commands = sys.argv[1], int(sys.argv[2]), [a.split("=", 1) for a in sys.argv[3:]]
times = {name: [] for name, _ in commands}
sizes = {}
with tempfile.TemporaryDirectory() as out:
    for _ in range(rounds):
        for name, command in commands:
            target = os.path.join(out, name + ".chamfer")
            argv = shlex.split(command)
            argv[1:1] = ["bake", mesh, "-o", target]
            start = time.perf_counter()
            subprocess.run(argv, check=True, stdout=subprocess.DEVNULL)
            times[name].append(time.perf_counter() - start)
            sizes[name] = os.path.getsize(target)
base = statistics.median(times[commands[0][0]])
print(f"| binary | median s ({rounds} rounds, interleaved) | min s | / {commands[0][0]} | file bytes |")
print("|---|---:|---:|---:|---:|")
for name, _ in commands:
    median = statistics.median(times[name])
    print(f"| {name} | {median:.3f} | {min(times[name]):.3f} | {median / base:.3f}× | {sizes[name]} |")
