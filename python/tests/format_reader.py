"""A reader of `.chamfer` assets in Python and numpy alone, written from docs/format.md (§n below).

It is a test of the document, not part of the package: if it reads every fixture as `chamfer.load`
does, a reader in any language can be written from the text. It reads the raw sections of every
format version (1 to 6) and applies the document's validation rules; a compact file's coded sections
(§4, docs/format-compact.md) it names but does not decode.
"""

import math
import struct

import numpy as np

MAGIC = b"CHAMFER\0"
MAX_HEADER_BYTES = 1 << 20
SECTION_ALIGN = 16
MAX_RING = 4096
CLUSTER_EDGES = 64
CLUSTER_BYTES = 48
KNOWN_FLAGS = (1 << 8) - 1

# §3 and §4: kind number -> name.
KINDS = {
    1: "render_positions",
    2: "render_normals",
    3: "mesh_indices",
    4: "topology_positions",
    5: "edge_vertices",
    6: "edge_attributes",
    7: "next_ends",
    8: "cap_heads",
    9: "intersection_segments",
    10: "intersection_polylines",
    11: "edge_clusters",
    12: "render_vertex_counts",
    13: "mesh_indices_coded",
    14: "topology_positions_coded",
    15: "render_normals_coded",
    16: "edge_corners",
    17: "edge_attributes_coded",
    18: "ring_orders",
    19: "render_vertex_counts_coded",
    20: "edge_clusters_coded",
    21: "skin_joints",
    22: "skin_weights",
    23: "morph_starts",
    24: "morph_vertices",
    25: "morph_deltas",
    26: "rig",
}
# §7: the last kind of each version's table.
LAST_KIND = {1: 8, 2: 10, 3: 11, 4: 12, 5: 20, 6: 26}
# §4: each coded kind and the raw kinds it replaces.
TWINS = {13: (3,), 14: (4,), 15: (2,), 16: (5,), 17: (6,), 18: (7, 8), 19: (12,), 20: (11,)}

EDGE_STATS = (
    "total", "kept", "boundary", "non_manifold", "crease", "ridge", "valley", "marked",
    "material", "smooth", "coplanar_dropped", "flipped", "marks_unmatched",
)  # fmt: skip


class FormatError(ValueError):
    """The bytes break a rule of docs/format.md."""


class CompactFile(FormatError):
    """The file codes sections (§4), which this reader does not decode."""


class _Fields:
    """§2's field encoding: little-endian, fixed-width integers, u64 lengths."""

    def __init__(self, data):
        self.data = data
        self.at = 0

    def take(self, n):
        if n > len(self.data) - self.at:
            raise FormatError("ends before its last field")
        piece = self.data[self.at : self.at + n]
        self.at += n
        return piece

    def unpack(self, fmt):
        return struct.unpack("<" + fmt, self.take(struct.calcsize("<" + fmt)))

    def u32(self):
        return self.unpack("I")[0]

    def u64(self):
        return self.unpack("Q")[0]

    def f32s(self, n):
        return self.unpack(f"{n}f")

    def string(self):
        try:
            return self.take(self.u64()).decode("utf-8")
        except UnicodeDecodeError:
            raise FormatError("text is not UTF-8") from None

    def option(self, read):
        tag = self.unpack("B")[0]
        if tag > 1:
            raise FormatError(f"an option's tag is {tag}")
        return read() if tag else None

    def variant(self, count):
        number = self.u32()
        if number >= count:
            raise FormatError(f"an enumeration holds an unknown variant {number}")
        return number

    def list(self, element_bytes, read):
        return [read() for _ in range(self.count(element_bytes))]

    def count(self, element_bytes):
        n = self.u64()
        if n * element_bytes > len(self.data) - self.at:
            raise FormatError("header list longer than the header")
        return n


# §3.9: numbers a key of each Target variant (None: its count field), values a key per Interpolation.
TARGET_NUMBERS = (3, 4, 3, None)
VALUES_PER_KEY = (1, 1, 3)
MAX_JOINTS = 1 << 16
WEIGHT_SUM_TOLERANCE = np.float32(1e-3)


def read_rig(data):
    """§3.9's Rig as a dict; an empty section is an empty rig."""
    fields = _Fields(bytes(data))
    if not len(data):
        return {"nodes": [], "joints": [], "morph_weights": [], "morph_names": [], "animations": []}

    def node():
        name = fields.string()
        parent = fields.option(fields.u32)
        return {"name": name, "parent": parent, "rest": fields.f32s(10)}

    def joint():
        return {"node": fields.u32(), "inverse_bind": fields.f32s(16)}

    def channel():
        kind = fields.variant(4)
        target = (kind, fields.unpack("2I") if kind == 3 else (fields.u32(),))
        interpolation = fields.variant(3)
        times = fields.list(4, lambda: fields.f32s(1)[0])
        values = fields.list(4, lambda: fields.f32s(1)[0])
        return {"target": target, "interpolation": interpolation, "times": times, "values": values}

    def animation():
        return {"name": fields.string(), "channels": fields.list(1, channel)}

    rig = {
        "nodes": fields.list(1, node),
        "joints": fields.list(68, joint),
        "morph_weights": fields.list(4, lambda: fields.f32s(1)[0]),
        "morph_names": fields.list(8, fields.string),
        "animations": fields.list(1, animation),
    }
    if fields.at != len(data):
        raise FormatError("rig: bytes are left after the rig")
    _check_rig(rig)
    return rig


def _check_rig(rig):
    """§3.9's rules of a rig."""
    finite = lambda values: all(math.isfinite(v) for v in values)  # noqa: E731
    nodes, targets = len(rig["nodes"]), len(rig["morph_weights"])
    if len(rig["joints"]) > MAX_JOINTS:
        raise FormatError("rig: more joints than an index names")
    for i, node in enumerate(rig["nodes"]):
        if node["parent"] is not None and node["parent"] >= i:
            raise FormatError(f"rig: node {i} comes before its parent")
        if not finite(node["rest"]):
            raise FormatError(f"rig: node {i}'s rest transform is not finite")
    for i, joint in enumerate(rig["joints"]):
        if joint["node"] >= nodes or not finite(joint["inverse_bind"]):
            raise FormatError(f"rig: joint {i} is not a node's, or not finite")
    if len(rig["morph_names"]) != targets or not finite(rig["morph_weights"]):
        raise FormatError("rig: morph names and weights disagree, or a weight is not finite")
    for animation in rig["animations"]:
        for channel in animation["channels"]:
            kind, numbers = channel["target"]
            if kind == 3:
                first, count = numbers
                if count == 0 or first + count > targets:
                    raise FormatError("rig: a channel sets morph targets the rig lacks")
                per_key = count
            else:
                if numbers[0] >= nodes:
                    raise FormatError("rig: a channel moves a node the rig lacks")
                per_key = TARGET_NUMBERS[kind]
            times, values = channel["times"], channel["values"]
            if not times or not finite(times) or any(b <= a for a, b in zip(times, times[1:])):
                raise FormatError("rig: a channel's key times are not finite and increasing")
            if len(values) != len(times) * per_key * VALUES_PER_KEY[channel["interpolation"]]:
                raise FormatError("rig: a channel's values do not fill its keys")
            if not finite(values):
                raise FormatError("rig: a channel's value is not finite")


def _motion(raw, v):
    """§3.9: the skin and morph sections checked against the rig and the V topology vertices."""
    rig = read_rig(raw("rig"))
    joints = _array(raw("skin_joints"), "skin_joints", np.uint16, 4)
    weights = _array(raw("skin_weights"), "skin_weights", np.float32, 4)
    if len(joints) or len(weights):
        if len(joints) != v or len(weights) != v:
            raise FormatError("skin_joints, skin_weights: not one per topology vertex")
        if (joints >= len(rig["joints"])).any():
            raise FormatError("skin_joints: a joint the rig lacks")
        if not np.isfinite(weights).all() or (weights < 0).any():
            raise FormatError("skin_weights: not finite, or negative")
        total = np.zeros(len(weights), np.float32)
        for k in range(4):
            total = (total + weights[:, k]).astype(np.float32)
        off = np.abs((total - np.float32(1)).astype(np.float32))
        if ((total != 0) & (off > WEIGHT_SUM_TOLERANCE)).any():
            raise FormatError("skin_weights: a vertex's weights do not sum to 1")
    starts = _array(raw("morph_starts"), "morph_starts", np.uint32, 1)
    vertices = _array(raw("morph_vertices"), "morph_vertices", np.uint32, 1)
    deltas = _array(raw("morph_deltas"), "morph_deltas", np.float32, 3)
    d = len(vertices)
    if len(starts) != len(rig["morph_weights"]) or len(deltas) != d:
        raise FormatError("morph_starts, morph_deltas: counts disagree with the rig or the vertices")
    ends = np.append(starts[1:].astype(np.int64), d)
    if len(starts) and (starts[0] != 0 or (ends < starts).any() or (ends > d).any()):
        raise FormatError("morph_starts: targets out of order")
    if not np.isfinite(deltas).all():
        raise FormatError("morph_deltas: not finite")
    if (vertices >= v).any():
        raise FormatError("morph_vertices: a vertex out of range")
    for start, end in zip(starts, ends):
        if (np.diff(vertices[start:end].astype(np.int64)) <= 0).any():
            raise FormatError("morph_vertices: not increasing within a target")
    return {"rig": rig, "skin_joints": joints, "skin_weights": weights, "morph_starts": starts,
            "morph_vertices": vertices, "morph_deltas": deltas}  # fmt: skip


def read_header(data):
    """§2: the header's fields as a dict."""
    fields = _Fields(data)
    header = {"source": fields.string(), "generator": fields.string()}
    header["settings"] = [(fields.string(), fields.string()) for _ in range(fields.count(16))]
    header["bounds_min"] = fields.f32s(3)
    header["bounds_max"] = fields.f32s(3)
    (header["radius_scale"],) = fields.f32s(1)
    stats = dict(zip(("input_vertices", "welded_vertices", "input_triangles",
                      "degenerate_triangles"), fields.unpack("4Q")))  # fmt: skip
    stats["edges"] = dict(zip(EDGE_STATS, fields.unpack(f"{len(EDGE_STATS)}Q")))
    edges, clamped = fields.unpack("2Q")
    radius_min, radius_max = fields.f32s(2)
    stats["chamfer"] = {"edges": edges, "clamped": clamped, "radius_min": radius_min,
                        "radius_max": radius_max}  # fmt: skip
    header["stats"] = stats
    header["sections"] = [fields.unpack("IQQ") for _ in range(fields.count(20))]
    if fields.at != len(data):
        raise FormatError(f"header is {fields.at} bytes but its length field says {len(data)}")
    numbers = header["bounds_min"] + header["bounds_max"]
    radii = (header["radius_scale"], radius_min, radius_max)
    if not all(math.isfinite(v) for v in numbers + radii) or min(radii) < 0:
        raise FormatError("bounds or radii not finite and non-negative")
    return header


def _section_table(header, version, header_end, file_len):
    """§2's section table rules: kind name -> (offset, length)."""
    kinds = range(1, LAST_KIND[version] + 1)
    table = {}
    previous_end = header_end
    for kind, offset, length in header["sections"]:
        if kind not in kinds:
            raise FormatError(f"unknown section kind {kind} for this format version")
        name = KINDS[kind]
        if offset % SECTION_ALIGN:
            raise FormatError(f"{name} starts at {offset}, not a multiple of {SECTION_ALIGN}")
        if offset < previous_end:
            raise FormatError(f"{name} overlaps what comes before it")
        if offset + length > file_len:
            raise FormatError(f"{name} is truncated")
        if name in table:
            raise FormatError(f"{name} appears twice")
        table[name] = (offset, length)
        previous_end = offset + length
    if previous_end < file_len:
        raise FormatError(f"{file_len - previous_end} unexpected bytes after the last section")
    for kind in kinds:
        if KINDS[kind] not in table:
            raise FormatError(f"{KINDS[kind]} is missing")
    return table


def _array(raw, name, dtype, row):
    """A section as a numpy array of rows of `row` elements."""
    width = np.dtype(dtype).itemsize * row
    if len(raw) % width:
        raise FormatError(f"{name}: {len(raw)} bytes is not a whole number of {width}-byte elements")
    values = np.frombuffer(raw, dtype=np.dtype(dtype).newbyteorder("<"))
    return values.reshape(-1, row) if row > 1 else values


def _floats(raw, name, row):
    values = _array(raw, name, np.float32, row)
    if not np.isfinite(values).all():
        raise FormatError(f"{name}: an element is not a finite number")
    return values


def _indices(raw, name, bound, row):
    """§3 Indices: u16 when the bound is at most 65 536, else u32, each below the bound."""
    dtype = np.uint16 if bound <= 1 << 16 else np.uint32
    values = _array(raw, name, dtype, row)
    if values.size and int(values.max()) >= bound:
        raise FormatError(f"{name}: index {int(values.max())} is not below {bound}")
    return values


def _clusters(raw, edges):
    """§3.8."""
    expected = -(-edges // CLUSTER_EDGES)
    if len(raw) != expected * CLUSTER_BYTES:
        raise FormatError(f"edge_clusters: {len(raw)} bytes for {edges} edges")
    record = np.dtype([("center", "<f4", 3), ("radius", "<f4"), ("axis", "<f4", 3),
                       ("cos_angle", "<f4"), ("flags", "<u4"), ("pad", "<u4", 3)])  # fmt: skip
    clusters = np.frombuffer(raw, dtype=record)
    numbers = [clusters["center"], clusters["radius"], clusters["axis"], clusters["cos_angle"]]
    if not all(np.isfinite(n).all() for n in numbers):
        raise FormatError("edge_clusters: an element is not a finite number")
    if (clusters["radius"] < 0).any() or (np.abs(clusters["cos_angle"]) > 1).any():
        raise FormatError("edge_clusters: radius negative or cosine outside [-1, 1]")
    if (clusters["flags"] & ~np.uint32(KNOWN_FLAGS)).any():
        raise FormatError("edge_clusters: unknown flag bits")
    return clusters


def _render_positions(stored, counts, topology_positions, render_vertices):
    """§3.1: the stored positions, or the topology positions repeated as the counts say."""
    if counts.size == 0:
        if len(stored) != render_vertices:
            raise FormatError(f"{render_vertices} normals for {len(stored)} render vertices")
        return stored
    if len(stored):
        raise FormatError("render_vertex_counts present beside render positions")
    if len(counts) != len(topology_positions):
        raise FormatError("render_vertex_counts: not one per topology vertex")
    if int(counts.sum(dtype=np.int64)) != render_vertices:
        raise FormatError("render_vertex_counts: do not sum to the render vertices")
    return np.repeat(topology_positions, counts, axis=0)


def _attributes(words):
    """§3.5: known flag bits, radii finite and non-negative."""
    if (words & (0xFFFF ^ KNOWN_FLAGS)).any():
        raise FormatError("edge_attributes: unknown flag bits")
    radii = (words >> 16).astype(np.uint16).view(np.float16)
    if not np.isfinite(radii).all() or (radii < 0).any():
        raise FormatError("edge_attributes: radius not finite and non-negative")


def _end_vertices(edge_vertices):
    """§3.4: the vertex at each edge end 2e + k (v0 for k = 0, v1 for k = 1)."""
    return edge_vertices[:, :2].reshape(-1)


def _rings(next_ends, cap_heads, end_vertices, vertices):
    """§3.6."""
    ends = len(end_vertices)
    if len(next_ends) not in (0, ends):
        raise FormatError(f"next_ends: {len(next_ends)} entries for {ends} edge ends")
    if len(next_ends) == 0 and len(cap_heads):
        raise FormatError("cap_heads: present without next_ends")
    if ends and np.bincount(end_vertices, minlength=vertices).max() > MAX_RING:
        raise FormatError(f"a vertex has more than {MAX_RING} edge ends")
    if len(next_ends):
        if (end_vertices[next_ends] != end_vertices).any():
            raise FormatError("next_ends: a next end is at another vertex")
        if len(np.unique(next_ends)) != ends:
            raise FormatError("next_ends: an end is the next of two ends")


def _intersections(segments, starts):
    """§3.7."""
    if (len(segments) == 0) != (len(starts) == 0):
        raise FormatError("intersection sections: one empty and not the other")
    if len(starts):
        if starts[0] != 0 or (np.diff(starts.astype(np.int64)) <= 0).any() or starts[-1] >= len(segments):
            raise FormatError("intersection_polylines: starts must be 0, then increase, below S")
    if (segments[:, 0] == segments[:, 1]).all(axis=1).any():
        raise FormatError("intersection_segments: a segment has zero length")
    bits = segments.view(np.uint32)
    continues = np.ones(len(segments), dtype=bool)
    continues[starts] = False
    joined = (bits[:-1, 1] == bits[1:, 0]).all(axis=1)
    if (continues[1:] & ~joined).any():
        raise FormatError("intersection_segments: a segment does not start where the one before ends")


def read(data):
    """Reads a `.chamfer` file's bytes: a dict with "version", "header" and one numpy array per raw
    section of §3 (the render positions rebuilt, §3.1). Raises FormatError naming the broken rule,
    CompactFile for a compact file."""
    data = memoryview(data).cast("B")
    if len(data) < 16:
        raise FormatError("truncated: the preamble needs 16 bytes")
    if bytes(data[:8]) != MAGIC:
        raise FormatError("not a .chamfer asset (bad magic bytes)")
    version, header_len = struct.unpack("<II", data[8:16])
    if version not in LAST_KIND:
        raise FormatError(f"format version {version} is not read (re-bake the source mesh)")
    if header_len > MAX_HEADER_BYTES:
        raise FormatError(f"header length {header_len} exceeds the limit")
    if 16 + header_len > len(data):
        raise FormatError("truncated: the header")
    header = read_header(bytes(data[16 : 16 + header_len]))
    table = _section_table(header, version, 16 + header_len, len(data))

    def raw(name):
        offset, length = table.get(name, (0, 0))
        return data[offset : offset + length]

    for coded, replaced in TWINS.items():
        if len(raw(KINDS[coded])):
            if any(len(raw(KINDS[r])) for r in replaced):
                raise FormatError(f"{KINDS[coded]} present beside the raw section it replaces")
            raise CompactFile(f"{KINDS[coded]} is coded (§4)")

    render_normals = _floats(raw("render_normals"), "render_normals", 3)
    topology_positions = _floats(raw("topology_positions"), "topology_positions", 3)
    edge_attributes = _array(raw("edge_attributes"), "edge_attributes", np.uint32, 1)
    r, v, e = len(render_normals), len(topology_positions), len(edge_attributes)
    counts = _array(raw("render_vertex_counts"), "render_vertex_counts", np.uint8, 1)
    stored = _floats(raw("render_positions"), "render_positions", 3)
    render_positions = _render_positions(stored, counts, topology_positions, r)
    mesh_indices = _indices(raw("mesh_indices"), "mesh_indices", r, 3)
    edge_vertices = _indices(raw("edge_vertices"), "edge_vertices", v, 4)
    if len(edge_vertices) != e:
        raise FormatError(f"edge_vertices: {len(edge_vertices)} edges for {e} edge attributes")
    _attributes(edge_attributes)
    next_ends = _indices(raw("next_ends"), "next_ends", 2 * e, 1)
    cap_heads = _indices(raw("cap_heads"), "cap_heads", 2 * e, 1)
    _rings(next_ends, cap_heads, _end_vertices(edge_vertices), v)
    segments = _floats(raw("intersection_segments"), "intersection_segments", 6).reshape(-1, 2, 3)
    starts = _array(raw("intersection_polylines"), "intersection_polylines", np.uint32, 1)
    _intersections(segments, starts)
    clusters_raw = raw("edge_clusters")
    # §3.8: absent before version 3, and may be left empty in version 5; then a reader computes them.
    has_clusters = version >= 3 and (len(clusters_raw) or version < 5)
    clusters = _clusters(clusters_raw, e) if has_clusters else None
    motion = _motion(raw, v)
    return {
        **motion,
        "version": version,
        "header": header,
        "render_positions": render_positions,
        "render_normals": render_normals,
        "mesh_indices": mesh_indices,
        "topology_positions": topology_positions,
        "edge_vertices": edge_vertices,
        "edge_attributes": edge_attributes,
        "edge_flags": (edge_attributes & 0xFFFF).astype(np.uint16),
        "edge_radii": (edge_attributes >> 16).astype(np.uint16).view(np.float16).astype(np.float32)
        * np.float32(header["radius_scale"]),
        "next_ends": next_ends,
        "cap_heads": cap_heads,
        "intersection_segments": segments,
        "intersection_starts": starts,
        "edge_clusters": clusters,
    }
