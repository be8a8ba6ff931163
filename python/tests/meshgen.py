"""A generated library of small meshes for the batch tests: boxes, prisms and tori of varied sizes,
written as OBJ, ASCII PLY, binary PLY, gzipped PLY and GLB, plus broken files of known kinds."""

import gzip
import json
import struct
from pathlib import Path

import numpy as np


def box(size):
    x, y, z = size
    v = np.array(
        [[0, 0, 0], [x, 0, 0], [x, y, 0], [0, y, 0], [0, 0, z], [x, 0, z], [x, y, z], [0, y, z]],
        dtype=np.float64,
    )
    f = np.array(
        [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
         [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]],
        dtype=np.int64,
    )
    return v, f


def prism(sides, radius, height):
    """A closed n-sided prism (a cylinder for large n)."""
    a = np.arange(sides) * 2 * np.pi / sides
    ring = np.stack([radius * np.cos(a), radius * np.sin(a), np.zeros(sides)], axis=1)
    v = np.concatenate([ring, ring + [0, 0, height], [[0, 0, 0], [0, 0, height]]])
    faces = []
    bottom, top = 2 * sides, 2 * sides + 1
    for i in range(sides):
        j = (i + 1) % sides
        faces += [[i, j, sides + j], [i, sides + j, sides + i], [bottom, j, i], [top, sides + i, sides + j]]
    return v, np.array(faces, dtype=np.int64)


def torus(major, minor, rings, sides):
    u = np.arange(rings) * 2 * np.pi / rings
    w = np.arange(sides) * 2 * np.pi / sides
    uu, ww = np.meshgrid(u, w, indexing="ij")
    r = major + minor * np.cos(ww)
    v = np.stack([r * np.cos(uu), r * np.sin(uu), minor * np.sin(ww)], axis=-1).reshape(-1, 3)
    faces = []
    for i in range(rings):
        for j in range(sides):
            a, b = i * sides + j, ((i + 1) % rings) * sides + j
            c, d = ((i + 1) % rings) * sides + (j + 1) % sides, i * sides + (j + 1) % sides
            faces += [[a, b, c], [a, c, d]]
    return v, np.array(faces, dtype=np.int64)


def obj_text(v, f):
    lines = [f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in v]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in f]
    return "\n".join(lines) + "\n"


def ply_ascii(v, f):
    head = (
        f"ply\nformat ascii 1.0\nelement vertex {len(v)}\nproperty float x\nproperty float y\n"
        f"property float z\nelement face {len(f)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    body = "".join(f"{x:.6f} {y:.6f} {z:.6f}\n" for x, y, z in v)
    body += "".join(f"3 {a} {b} {c}\n" for a, b, c in f)
    return (head + body).encode()


def ply_binary(v, f):
    head = (
        f"ply\nformat binary_little_endian 1.0\nelement vertex {len(v)}\nproperty float x\n"
        f"property float y\nproperty float z\nelement face {len(f)}\n"
        "property list uchar int vertex_indices\nend_header\n"
    ).encode()
    body = v.astype("<f4").tobytes()
    faces = np.zeros(len(f), dtype=[("n", "u1"), ("i", "<i4", 3)])
    faces["n"], faces["i"] = 3, f
    return head + body + faces.tobytes()


def glb(v, f):
    positions = v.astype("<f4").tobytes()
    indices = f.astype("<u4").tobytes()
    lo, hi = v.min(axis=0).astype(np.float32), v.max(axis=0).astype(np.float32)
    document = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(positions) + len(indices)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(positions)},
            {"buffer": 0, "byteOffset": len(positions), "byteLength": len(indices)},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(v), "type": "VEC3",
             "min": [float(c) for c in lo], "max": [float(c) for c in hi]},
            {"bufferView": 1, "componentType": 5125, "count": 3 * len(f), "type": "SCALAR"},
        ],
    }
    text = json.dumps(document).encode()
    text += b" " * (-len(text) % 4)
    binary = positions + indices
    binary += b"\0" * (-len(binary) % 4)
    chunks = struct.pack("<I4s", len(text), b"JSON") + text + struct.pack("<I4s", len(binary), b"BIN\0") + binary
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


#: The broken files: name -> (bytes, the exception class bake raises).
BROKEN = {
    "broken-truncated.ply": (
        b"ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty float x\n"
        b"property float y\nproperty float z\nelement face 12\n"
        b"property list uchar int vertex_indices\nend_header\n" + b"\0" * 40,
        "FormatError",
    ),
    "broken-nan.obj": (b"v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n", "FormatError"),  # refused at its line
    "broken-index.obj": (b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "FormatError"),
    "broken-empty.obj": (b"# nothing here\n", "MeshError"),
    "broken-garbage.glb": (b"glTF\x02\0\0\0" + b"\xff" * 64, "FormatError"),
}


def write_library(folder: Path, count: int = 200, seed: int = 27) -> dict:
    """Writes ``count`` meshes (the last 5 of them broken) into ``folder``, some in sub-folders;
    returns {file name: the exception class name} of the broken ones."""
    rng = np.random.default_rng(seed)
    (folder / "props").mkdir(parents=True, exist_ok=True)
    good = count - len(BROKEN)
    for n in range(good):
        kind = n % 3
        if kind == 0:
            v, f = box(rng.uniform(0.5, 3.0, size=3))
        elif kind == 1:
            v, f = prism(int(rng.integers(3, 40)), rng.uniform(0.2, 2), rng.uniform(0.2, 3))
        else:
            v, f = torus(rng.uniform(1, 3), rng.uniform(0.1, 0.6), int(rng.integers(6, 24)), int(rng.integers(4, 12)))
        v = v + rng.uniform(-10, 10, size=3)
        fmt = n % 5
        where = folder / "props" if n % 7 == 0 else folder
        stem = f"mesh-{n:03d}"
        if fmt == 0:
            (where / f"{stem}.obj").write_text(obj_text(v, f))
        elif fmt == 1:
            (where / f"{stem}.ply").write_bytes(ply_ascii(v, f))
        elif fmt == 2:
            (where / f"{stem}.ply").write_bytes(ply_binary(v, f))
        elif fmt == 3:
            (where / f"{stem}.ply.gz").write_bytes(gzip.compress(ply_binary(v, f), mtime=0))
        else:
            (where / f"{stem}.glb").write_bytes(glb(v, f))
    for name, (data, _) in BROKEN.items():
        (folder / name).write_bytes(data)
    return {name: kind for name, (_, kind) in BROKEN.items()}
