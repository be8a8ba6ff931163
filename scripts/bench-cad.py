#!/usr/bin/env python3
"""STL and 3MF in, and stitching, for BENCHMARKS.md "STL and 3MF (issue 30)"; run by scripts/bench-cad.sh.

    bench-cad.py make MESH.ply OUT_DIR      bunny.stl (binary soup), bunny-ascii.stl, bunny.3mf, cracked.obj (a cube
                                            tessellated face by face, about 0.5 M triangles)
    bench-cad.py trimesh FILE               trimesh.load(FILE, process=False) and with its default
                                            processing (merge), seconds as JSON (imports not counted)
    bench-cad.py all --chamfer BIN --peer BIN --rounds N OUT_DIR MESH.ply
                                            every row, round after round in the same run, as Markdown
"""
import io
import json
import os
import re
import statistics
import struct
import subprocess
import sys
import time
import zipfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


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
    # 3MF: one object, one build item, deflated as writers do.
    model = io.StringIO()
    model.write('<?xml version="1.0" encoding="UTF-8"?>\n<model unit="millimeter" '
                'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources><object id="1" type="model"><mesh><vertices>\n')
    model.writelines('<vertex x="%.9g" y="%.9g" z="%.9g"/>\n' % tuple(p) for p in positions.tolist())
    model.write("</vertices><triangles>\n")
    model.writelines('<triangle v1="%d" v2="%d" v3="%d"/>\n' % tuple(t) for t in triangles.tolist())
    model.write('</triangles></mesh></object></resources><build><item objectid="1"/></build></model>\n')
    rels = ('<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
            '<Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>')
    types = ('<?xml version="1.0" encoding="UTF-8"?><Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
             '<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
             '<Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>')
    with zipfile.ZipFile(os.path.join(out, "bunny.3mf"), "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("[Content_Types].xml", types)
        z.writestr("_rels/.rels", rels)
        z.writestr("3D/3dmodel.model", model.getvalue())
    cracked(os.path.join(out, "cracked.obj"))


def cracked(path):
    """A unit cube whose six faces are tessellated on their own, on grids of 200 to 205 cells a side,
    so every edge where two faces meet is a crack of T-junctions (the fixture box-cracked.obj, large)."""
    lines, base = [], 1
    faces = []
    for axis in range(3):
        for side in (0.0, 1.0):
            u, v = [0.0] * 3, [0.0] * 3
            u[(axis + 1) % 3], v[(axis + 2) % 3] = 1.0, 1.0
            if side == 0.0:
                u, v = v, u
            o = [0.0] * 3
            o[axis] = side
            faces.append((o, u, v))
    for k, (o, u, v) in enumerate(faces):
        nu, nv = 200 + k, 205 - k
        for j in range(nv + 1):
            for i in range(nu + 1):
                p = [o[c] + u[c] * i / nu + v[c] * j / nv for c in range(3)]
                lines.append("v %.9g %.9g %.9g" % tuple(p))
        for j in range(nv):
            for i in range(nu):
                a = base + j * (nu + 1) + i
                b, c, d = a + 1, a + nu + 2, a + nu + 1
                lines.append("f %d %d %d" % (a, b, c))
                lines.append("f %d %d %d" % (a, c, d))
        base += (nu + 1) * (nv + 1)
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


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
