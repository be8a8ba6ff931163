#!/usr/bin/env python3
"""Benchmarks of the Python package (issue 27), every figure measured round after round in one run.

  .venv/bin/python scripts/bench-python.py [--rounds 3] [--chamfer target/release/chamfer]

folders: files/s and MB/s of baking a folder (a) in one process (bake_if_changed file after file, no
Dask), (b) on a LocalCluster of 2 worker processes (chamfer.dask.bake_folder, cluster started
before the clock), (c) by `chamfer bake FOLDER -o OUT` (one process, rayon over the files), each
into a fresh output folder. Two folders: the 200 generated meshes of the Dask tests (5 broken), and
the bundled meshes of fixtures/meshes without bunny-loop2, four copies of each.

calls: the wall time of one bake, from Python (`chamfer.bake(path).save(out)`, in process) against
the `chamfer bake MESH -o OUT` process, on fandisk and bunny-loop2; medians.
"""

import argparse
import logging
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python" / "tests"))

import chamfer  # noqa: E402
import meshgen  # noqa: E402
from chamfer.dask import bake_folder  # noqa: E402


def timed(work):
    start = time.perf_counter()
    work()
    return time.perf_counter() - start


def folder_bytes(folder):
    return sum(p.stat().st_size for p in folder.rglob("*") if p.is_file())


def serial(src, dst):
    for input, output in chamfer.plan_folder(src, dst):
        try:
            chamfer.bake_if_changed(input, output)
        except chamfer.ChamferError:
            pass


def bench_folders(cli, rounds, scratch):
    from distributed import Client, LocalCluster

    generated = scratch / "generated"
    meshgen.write_library(generated)
    bundled = scratch / "bundled"
    bundled.mkdir()
    for mesh in sorted((ROOT / "fixtures" / "meshes").iterdir()):
        if mesh.suffix == ".obj":
            for copy in range(4):
                shutil.copy(mesh, bundled / f"{mesh.stem}-{copy}.obj")
    start = time.perf_counter()
    cluster = LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None, silence_logs=logging.ERROR
    )
    client = Client(cluster)
    startup = time.perf_counter() - start
    print(f"LocalCluster of 2 worker processes started in {startup:.2f} s (not counted below)")
    runs = {
        "one process (no Dask)": lambda s, d: serial(s, d),
        "LocalCluster, 2 workers": lambda s, d: bake_folder(s, d, client),
        "chamfer bake (CLI, rayon)": lambda s, d: subprocess.run(
            [cli, "bake", s, "-o", d], capture_output=True, check=False
        ),
    }
    for folder in [generated, bundled]:
        files = len(chamfer.plan_folder(folder, scratch / "plan"))
        megabytes = folder_bytes(folder) / 1e6
        times = {name: [] for name in runs}
        for round in range(rounds):
            order = list(runs.items())
            if round % 2:
                order.reverse()
            for name, run in order:
                dst = scratch / "out"
                shutil.rmtree(dst, ignore_errors=True)
                times[name].append(timed(lambda: run(folder, dst)))
        print(f"\n{folder.name}: {files} files, {megabytes:.1f} MB, {rounds} rounds, medians")
        print("| run | seconds | files/s | MB/s | vs one process |")
        print("|---|---:|---:|---:|---:|")
        base = statistics.median(times["one process (no Dask)"])
        for name, samples in times.items():
            s = statistics.median(samples)
            print(f"| {name} | {s:.2f} | {files / s:.1f} | {megabytes / s:.2f} | {base / s:.2f}× |")
    client.close()
    cluster.close()


def bench_calls(cli, rounds, scratch):
    print("\none bake, wall time in ms, medians")
    print("| mesh | rounds | `chamfer bake` process | Python `bake().save()` | Python `bake()` | Python − CLI | Python / CLI |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for mesh, n in [(ROOT / "fixtures" / "meshes" / "fandisk.obj", 5 * rounds), (ROOT / "fixtures" / "meshes" / "bunny-loop2.ply.gz", rounds)]:
        out = scratch / "call.chamfer"
        runs = {
            "cli": lambda: subprocess.run([cli, "bake", mesh, "-o", out], capture_output=True, check=True),
            "save": lambda: chamfer.bake(mesh).save(out),
            "bake": lambda: chamfer.bake(mesh),
        }
        times = {name: [] for name in runs}
        for round in range(n):
            order = list(runs.items())
            if round % 2:
                order.reverse()
            for name, run in order:
                times[name].append(timed(run) * 1e3)
        cli_ms, save_ms, bake_ms = (statistics.median(times[k]) for k in ("cli", "save", "bake"))
        print(
            f"| {mesh.name} | {n} | {cli_ms:.1f} | {save_ms:.1f} | {bake_ms:.1f} | {save_ms - cli_ms:+.1f} | "
            f"{save_ms / cli_ms:.2f} |"
        )
    imports = [
        timed(lambda: subprocess.run([sys.executable, "-c", "import chamfer"], check=True)) * 1e3 for _ in range(5)
    ]
    python = [timed(lambda: subprocess.run([sys.executable, "-c", "pass"], check=True)) * 1e3 for _ in range(5)]
    print(
        f"\n`python -c 'import chamfer'`: {statistics.median(imports):.1f} ms "
        f"(`python -c pass`: {statistics.median(python):.1f} ms)"
    )


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("what", nargs="?", choices=["all", "folders", "calls"], default="all")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--chamfer", default=str(ROOT / "target" / "release" / "chamfer"))
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        scratch = Path(scratch)
        if args.what in ("all", "folders"):
            bench_folders(args.chamfer, args.rounds, scratch)
        if args.what in ("all", "calls"):
            bench_calls(args.chamfer, args.rounds, scratch)


if __name__ == "__main__":
    main()
