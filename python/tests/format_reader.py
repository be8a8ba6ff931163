"""A reader of `.chamfer` assets in Python and numpy alone, written from docs/format.md (§n below).

It is a test of the document, not part of the package: if it reads every fixture as `chamfer.load`
does, a reader in any language can be written from the text. It reads the raw sections of every
format version (1 to 5) and applies the document's validation rules; a compact file's coded sections
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
}
# §7: the last kind of each version's table.
LAST_KIND = {1: 8, 2: 10, 3: 11, 4: 12, 5: 20}
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
            raise FormatError("header ends before its last field")
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
            raise FormatError("header text is not UTF-8") from None

    def count(self, element_bytes):
        n = self.u64()
        if n * element_bytes > len(self.data) - self.at:
            raise FormatError("header list longer than the header")
        return n


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
    return {
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
