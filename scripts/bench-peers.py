#!/usr/bin/env python3
"""Bake speed against peers, for BENCHMARKS.md "Bake speed (issue 15)"; run by scripts/bench-peers.sh.

    bench-peers.py trimesh MESH.ply        load + merge_vertices + face_adjacency + face_adjacency_angles
    bench-peers.py remap MESH.ply [RUNS]   meshoptimizer's generate_vertex_remap on the PLY's vertex
                                           positions and on its triangles' corner positions
    bench-peers.py all --chamfer BIN [--base BIN] --three DIR --weld-bench BIN [--rounds N]
                   [--builds-only] MESH.ply

The first two print one JSON object with the seconds of each step (imports and interpreter start not
counted). `all` runs, round after round in the same run, `chamfer bake --timings` (and a baseline
build of it), trimesh, three.js's EdgesGeometry (scripts/bench-three.mjs), meshoptimizer's remap and
our weld (the bench_weld_remap example), each in a fresh process, and prints Markdown tables of the
medians with the ratios.
"""
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time


def ply_body(path):
    """(vertex positions as an (n, 3) float32 array, triangles as an (m, 3) uint32 array) of a
    binary little-endian PLY of float vertex properties and `uchar` + 32-bit triangle lists."""
    import numpy as np

    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    if "format binary_little_endian 1.0" not in header:
        raise SystemExit(f"{path}: only binary little-endian PLY is read here")
    counts, names, element = {}, [], None
    for line in header:
        words = line.split()
        if words[:1] == ["element"]:
            element = words[1]
            counts[element] = int(words[2])
        elif element == "vertex" and words[:1] == ["property"]:
            if words[1] != "float":
                raise SystemExit(f"{path}: vertex property {words[-1]} is not a float")
            names.append(words[-1])
    if names[:3] != ["x", "y", "z"]:
        raise SystemExit(f"{path}: vertex properties do not start with x y z")
    n, m = counts["vertex"], counts.get("face", 0)
    table = np.frombuffer(data, dtype="<f4", count=n * len(names), offset=end)
    positions = np.ascontiguousarray(table.reshape(n, len(names))[:, :3])
    faces = np.frombuffer(data, dtype=np.uint8, count=m * 13, offset=end + n * len(names) * 4)
    faces = faces.reshape(m, 13)
    if not (faces[:, 0] == 3).all():
        raise SystemExit(f"{path}: faces are not all triangles")
    triangles = np.ascontiguousarray(faces[:, 1:]).view("<u4").reshape(m, 3)
    return positions, triangles


def trimesh_steps(path):
    import trimesh

    out = {}
    start = time.perf_counter()
    mesh = trimesh.load(path, process=False)
    out["load"] = time.perf_counter() - start
    step = time.perf_counter()
    mesh.merge_vertices()
    out["merge_vertices"] = time.perf_counter() - step
    step = time.perf_counter()
    adjacency = mesh.face_adjacency
    out["face_adjacency"] = time.perf_counter() - step
    step = time.perf_counter()
    angles = mesh.face_adjacency_angles
    out["face_adjacency_angles"] = time.perf_counter() - step
    out["total"] = time.perf_counter() - start
    out["faces"] = len(mesh.faces)
    out["adjacent_pairs"] = len(adjacency)
    out["angles"] = len(angles)
    out["version"] = trimesh.__version__
    return out


def remap(path, runs):
    import ctypes
    from importlib.metadata import version

    import numpy as np
    from meshoptimizer._loader import lib

    positions, triangles = ply_body(path)
    out = {"version": version("meshoptimizer")}
    corners = np.ascontiguousarray(positions[triangles.reshape(-1)])
    for name, points in [("vertices", positions), ("corners", corners)]:
        destination = np.zeros(len(points), dtype=np.uint32)
        times = []
        for _ in range(runs):
            # The C function itself, unindexed (indices NULL, index_count = vertex count): the
            # Python wrapper passes index_count 0 when there are no indices, which remaps nothing.
            start = time.perf_counter()
            unique = lib.meshopt_generateVertexRemap(
                destination.ctypes.data_as(ctypes.POINTER(ctypes.c_uint)),
                None,
                len(points),
                points.ctypes.data_as(ctypes.c_void_p),
                len(points),
                12,
            )
            times.append(time.perf_counter() - start)
        out[name] = {"remap": statistics.median(times), "count": len(points), "unique": int(unique)}
    return out


STAGES = ["parse", "weld", "adjacency", "classify", "caps", "intersections", "normals", "assemble", "write"]


def bake(binary, mesh):
    """Whole-process wall seconds of `chamfer bake --timings`, its stages (ms) and peak RSS (MB)."""
    with tempfile.TemporaryDirectory() as out:
        start = time.perf_counter()
        run = subprocess.run(
            [binary, "bake", mesh, "-o", os.path.join(out, "m.chamfer"), "--timings"],
            check=True,
            capture_output=True,
            text=True,
        )
        wall = time.perf_counter() - start
        size = os.path.getsize(os.path.join(out, "m.chamfer"))
    text = run.stdout
    sample = {"wall": wall, "asset_bytes": size}
    for stage in STAGES:
        sample[stage] = float(re.search(rf"{stage} ([0-9.]+)", text).group(1))
    sample["processing"] = float(re.search(r"processing \(all but parse\): ([0-9.]+) ms", text).group(1))
    sample["mesh_mb"] = float(re.search(r"mesh ([0-9.]+) MB", text).group(1))
    sample["peak_mb"] = float(re.search(r"peak RSS ([0-9.]+) MB", text).group(1))
    return sample


def ply_triangle_count(path):
    with open(path, "rb") as f:
        header = f.read(4096).split(b"end_header")[0].decode("ascii", "replace")
    return int(re.search(r"element face ([0-9]+)", header).group(1))


def child_json(command):
    run = subprocess.run(command, check=True, capture_output=True, text=True)
    return json.loads(run.stdout.strip().splitlines()[-1])


def median(samples, key):
    return statistics.median(s[key] for s in samples)


def run_all(args):
    options = {"--chamfer": None, "--base": None, "--three": None, "--weld-bench": None, "--rounds": "5"}
    mesh = None
    builds_only = False
    it = iter(args)
    for arg in it:
        if arg == "--builds-only":
            builds_only = True
        elif arg in options:
            options[arg] = next(it)
        else:
            mesh = arg
    rounds = int(options["--rounds"])
    here = os.path.dirname(os.path.abspath(__file__))
    builds = {"ours": options["--chamfer"]}
    if options["--base"]:
        builds["base"] = options["--base"]
    samples = {name: [] for name in builds}
    peers = {"trimesh": [], "three": [], "remap": [], "weld": []}
    for round_ in range(rounds):
        # Every other round in the other order: the first bake after the peers' processes pays for
        # the kernel's clean-up after them (its write stage most), which must not favour a build.
        order = list(builds.items())
        for name, binary in order if round_ % 2 == 0 else order[::-1]:
            samples[name].append(bake(binary, mesh))
        if builds_only:
            continue
        peers["trimesh"].append(child_json([sys.executable, __file__, "trimesh", mesh]))
        if options["--three"]:
            peers["three"].append(
                child_json(["node", os.path.join(here, "bench-three.mjs"), options["--three"], mesh])
            )
        peers["remap"].append(child_json([sys.executable, __file__, "remap", mesh, "5"]))
        peers["weld"].append(child_json([options["--weld-bench"], mesh, "5"]))

    print(f"mesh: {os.path.basename(mesh)}, rounds: {rounds} (medians)\n")
    print("| build | " + " | ".join(STAGES) + " | processing ms | M tri/s (processing) | whole process ms | mesh MB | peak RSS MB | peak / mesh | asset B/triangle |")
    print("|---|" + "---:|" * (len(STAGES) + 8))
    triangles = peers["trimesh"][0]["faces"] if peers["trimesh"] else ply_triangle_count(mesh)
    for name in builds:
        s = samples[name]
        cells = [f"{median(s, k):.1f}" for k in STAGES]
        processing = median(s, "processing")
        print(
            f"| {name} | " + " | ".join(cells)
            + f" | {processing:.0f} | {triangles / processing / 1e3:.2f} | {median(s, 'wall') * 1e3:.0f}"
            + f" | {median(s, 'mesh_mb'):.1f} | {median(s, 'peak_mb'):.1f} | {median(s, 'peak_mb') / median(s, 'mesh_mb'):.2f}×"
            + f" | {median(s, 'asset_bytes') / triangles:.1f} |"
        )
    ours = median(samples["ours"], "wall")
    if "base" in builds:
        b = median(samples["base"], "wall")
        print(f"\nwhole process: base {b:.3f} s, ours {ours:.3f} s, {b / ours:.2f}× faster")
    if builds_only:
        return
    print("\n| peer | version | peer s | chamfer bake whole process s | ratio (target) |")
    print("|---|---|---:|---:|---:|")
    t = median(peers["trimesh"], "total")
    print(f"| trimesh load + merge_vertices + face_adjacency + face_adjacency_angles | {peers['trimesh'][0]['version']} | {t:.2f} | {ours:.3f} | {t / ours:.1f}× (≥ 20×) |")
    if peers["three"]:
        e = median(peers["three"], "edges_geometry")
        print(f"| three.js EdgesGeometry(geometry, 30) alone | {peers['three'][0]['version']} | {e:.2f} | {ours:.3f} | {e / ours:.1f}× (≥ 25×) |")
    print("\n| positions | count | unique | meshoptimizer generate_vertex_remap ms | our exact weld ms | ours / meshopt (target ≤ 1.2) | our default-tolerance weld ms |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for name in ["vertices", "corners"]:
        r = statistics.median(p[name]["remap"] for p in peers["remap"])
        w = statistics.median(p[name]["weld_exact"] for p in peers["weld"])
        d = statistics.median(p[name]["weld_default"] for p in peers["weld"])
        first = peers["weld"][0][name]
        print(f"| {name} | {first['count']} | {first['unique']} | {r * 1e3:.1f} | {w * 1e3:.1f} | {w / r:.2f} | {d * 1e3:.1f} |")
    print(f"\nmeshoptimizer (Python package) {peers['remap'][0]['version']}; our weld on {peers['weld'][0]['threads']} threads.")


def main():
    mode = sys.argv[1] if len(sys.argv) > 1 else ""
    if mode == "trimesh":
        print(json.dumps(trimesh_steps(sys.argv[2])))
    elif mode == "remap":
        print(json.dumps(remap(sys.argv[2], int(sys.argv[3]) if len(sys.argv) > 3 else 5)))
    elif mode == "all":
        run_all(sys.argv[2:])
    else:
        raise SystemExit(__doc__)


if __name__ == "__main__":
    main()
