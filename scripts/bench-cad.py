#!/usr/bin/env python3
"""STL and 3MF in, and stitching, for BENCHMARKS.md "STL and 3MF (issue 30)"; run by scripts/bench-cad.sh.

    bench-cad.py make MESH.ply OUT_DIR      bunny.stl (binary soup), bunny-ascii.stl, bunny.3mf, cracked.obj (a cube
                                            tessellated face by face, about 0.5 M triangles)
    bench-cad.py trimesh FILE               trimesh.load(FILE, process=False) and with its default
                                            processing (merge), seconds as JSON (imports not counted)
    bench-cad.py all --chamfer BIN --peer BIN --rounds N OUT_DIR MESH.ply
                                            every row, round after round in the same run, as Markdown
"""
import json
import os
import re
import statistics
import struct
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.join(HERE, "..", "fixtures")]


def make(ply, out):
    import numpy as np
    from importlib import import_module

    positions, triangles = import_module("bench-peers").ply_body(ply)
    corners = positions[triangles]  # (m, 3, 3): the soup
    m = len(triangles)
    record = np.zeros(m, dtype=[("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])
    record["corners"] = corners
    with open(os.path.join(out, "bunny.stl"), "wb") as f:
        f.write(b"solid bunny-loop2 as binary".ljust(80, b" ") + struct.pack("<I", m))
        f.write(record.tobytes())
    with open(os.path.join(out, "bunny-ascii.stl"), "w") as f:
        f.write("solid bunny-loop2\n")
        for t in corners.tolist():
            f.write(" facet normal 0 0 0\n  outer loop\n")
            f.write("".join("   vertex %.9g %.9g %.9g\n" % tuple(p) for p in t))
            f.write("  endloop\n endfacet\n")
        f.write("endsolid bunny-loop2\n")
    # 3MF (one object, one build item) and the cracked cube, as the fixtures make them, large.
    fixtures = import_module("make_fixtures")
    write = fixtures.write
    write(os.path.join(out, "bunny.3mf"), fixtures.threemf(
        [(1, fixtures.threemf_mesh(positions.tolist(), triangles.tolist()))], [(1, None)]))
    # Grids of 200 to 205 cells a side: about 0.5 M triangles, every cube edge a crack of T-junctions.
    write(os.path.join(out, "cracked.obj"), fixtures.obj(*fixtures.box_cracked(lambda k: (200 + k, 205 - k))))


def trimesh_times(path):
    import trimesh

    start = time.perf_counter()
    raw = trimesh.load(path, process=False, force="mesh")
    parse = time.perf_counter() - start
    start = time.perf_counter()
    merged = trimesh.load(path, force="mesh")
    processed = time.perf_counter() - start
    print(json.dumps({"parse": parse, "parse_and_merge": processed,
                      "faces": len(raw.faces), "merged_vertices": len(merged.vertices)}))


def wall(command):
    start = time.perf_counter()
    run = subprocess.run(command, capture_output=True, text=True, check=True)
    return time.perf_counter() - start, run.stdout


def report(chamfer, peer, rounds, out, ply):
    stl, threemf, cracked_obj = (os.path.join(out, n) for n in ("bunny.stl", "bunny.3mf", "cracked.obj"))
    asset = os.path.join(out, "x.chamfer")
    rows = {}

    def add(name, seconds):
        rows.setdefault(name, []).append(seconds)

    peer_runs, ascii_runs, trimesh_runs, stitch_lines = [], [], {}, {}
    ascii_stl = os.path.join(out, "bunny-ascii.stl")
    for _ in range(rounds):
        for name, path in [("ply", ply), ("stl", stl), ("3mf", threemf)]:
            add("bake " + name, wall([chamfer, "bake", path, "-o", asset])[0])
        for flag in ([], ["--no-stitch"]):
            seconds, text = wall([chamfer, "bake", cracked_obj, "-o", asset, "--timings"] + flag)
            add("bake cracked " + (" ".join(flag) or "default"), seconds)
            stitch = re.search(r"stitch ([0-9.]+)", text)
            add("stitch step " + (" ".join(flag) or "default"), float(stitch.group(1)) / 1000 if stitch else 0.0)
            stitch_lines[" ".join(flag) or "default"] = text.strip().splitlines()[:2]
        peer_runs.append(json.loads(subprocess.run([peer, stl, "1"], capture_output=True, text=True, check=True).stdout))
        ascii_runs.append(json.loads(subprocess.run([peer, ascii_stl, "1"], capture_output=True, text=True, check=True).stdout))
        for name, path in [("stl", stl), ("3mf", threemf)]:
            result = subprocess.run([sys.executable, __file__, "trimesh", path], capture_output=True, text=True)
            if result.returncode == 0:
                trimesh_runs.setdefault(name, []).append(json.loads(result.stdout))
            else:
                trimesh_runs.setdefault(name, []).append({"error": result.stderr.strip().splitlines()[-1]})
    med = lambda xs: statistics.median(xs)
    print("| step | median s (%d rounds) | ratio |" % rounds)
    print("|---|---|---|")
    load = med([r["chamfer_load"] for r in peer_runs])
    rows_peer = [
        ("Chamfer `load::load` of bunny.stl (soup)", load),
        ("Chamfer `load::load` + default weld", med([r["chamfer_load_weld"] for r in peer_runs])),
        ("stl_io 0.11 `create_stl_reader` (soup)", med([r["stl_io_soup"] for r in peer_runs])),
        ("stl_io 0.11 `read_stl` (indexed)", med([r["stl_io_indexed"] for r in peer_runs])),
        ("of which Chamfer reading the file (`std::fs::read`)", med([r["read_file"] for r in peer_runs])),
        ("of which Chamfer parsing it in memory", med([r["chamfer_parse_in_memory"] for r in peer_runs])),
        ("Chamfer `load::load` of bunny-ascii.stl", med([r["chamfer_load"] for r in ascii_runs])),
        ("stl_io 0.11 `create_stl_reader` of bunny-ascii.stl", med([r["stl_io_soup"] for r in ascii_runs])),
    ]
    for name, key in [("stl", "STL"), ("3mf", "3MF")]:
        ok = [r for r in trimesh_runs.get(name, []) if "parse" in r]
        if ok:
            rows_peer.append(("trimesh %s load, process=False" % key, med([r["parse"] for r in ok])))
            rows_peer.append(("trimesh %s load (merge)" % key, med([r["parse_and_merge"] for r in ok])))
        else:
            print("trimesh %s: %s" % (key, trimesh_runs.get(name, [{}])[0]), file=sys.stderr)
    for name, seconds in rows_peer:
        print("| %s | %.3f | %.2f× |" % (name, seconds, seconds / load))
    print()
    base = med(rows["bake ply"])
    print("| whole-process `chamfer bake` | median s | ratio to PLY |")
    print("|---|---|---|")
    for name in ["bake ply", "bake stl", "bake 3mf", "bake cracked default", "bake cracked --no-stitch",
                 "stitch step default", "stitch step --no-stitch"]:
        print("| %s | %.3f | %.2f× |" % (name, med(rows[name]), med(rows[name]) / base))
    print()
    print("peer counts:", json.dumps({k: v for k, v in peer_runs[0].items() if "vertices" in k or "triangles" in k}))
    for flag, lines in stitch_lines.items():
        print("cracked (%s):" % flag, " / ".join(lines))


def main():
    if sys.argv[1] == "make":
        make(sys.argv[2], sys.argv[3])
    elif sys.argv[1] == "trimesh":
        trimesh_times(sys.argv[2])
    elif sys.argv[1] == "all":
        args = sys.argv[2:]
        opts = {args[i]: args[i + 1] for i in range(0, len(args) - 2, 2)}
        report(opts["--chamfer"], opts["--peer"], int(opts["--rounds"]), args[-2], args[-1])


if __name__ == "__main__":
    main()
