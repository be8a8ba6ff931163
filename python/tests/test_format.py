"""docs/format.md is enough to read an asset: format_reader.py, written from it in Python and numpy
alone, reads every fixture asset and every fresh bake of the fixture meshes to the arrays
`chamfer.load` gives, and rejects exactly the damaged files the Rust decoder rejects."""

import numpy as np
import pytest

import chamfer
import format_reader
from conftest import FIXTURES, MESHES, SHAPES, mesh_files

SECTIONS = (
    "render_positions", "render_normals", "mesh_indices", "topology_positions", "edge_vertices",
    "edge_attributes", "edge_flags", "edge_radii", "next_ends", "cap_heads",
    "intersection_segments", "intersection_starts",
)  # fmt: skip
OLD_ASSETS = sorted((FIXTURES / "assets").glob("*.chamfer"))


def assert_same(read, asset):
    """Every section and header field the reader gives equals chamfer's."""
    for name in SECTIONS:
        expected = np.asarray(getattr(asset, name))
        got = read[name]
        assert got.dtype == expected.dtype, name
        np.testing.assert_array_equal(got.reshape(expected.shape), expected, err_msg=name)
    for mine, theirs in [("skin_joints", "joints"), ("skin_weights", "weights"),
                         ("morph_starts", "morph_starts"), ("morph_vertices", "morph_vertices"),
                         ("morph_deltas", "morph_deltas")]:  # fmt: skip
        expected = np.asarray(getattr(asset, theirs))
        assert read[mine].dtype == expected.dtype, mine
        np.testing.assert_array_equal(read[mine].reshape(expected.shape), expected, err_msg=mine)
    rig, summary = read["rig"], asset.rig
    assert len(rig["joints"]) == summary["joints"]
    assert [n["name"] for n in rig["nodes"]] == summary["nodes"]
    assert rig["morph_names"] == summary["morph_targets"]
    assert [(a["name"], len(a["channels"])) for a in rig["animations"]] == [
        (a["name"], a["channels"]) for a in summary["animations"]
    ]
    header = read["header"]
    assert header["source"] == asset.source
    assert header["generator"] == asset.generator
    assert dict(header["settings"]) == asset.settings
    assert (header["bounds_min"], header["bounds_max"]) == tuple(map(tuple, asset.bounds))
    stats = asset.stats
    mine = header["stats"]
    assert (mine["input_vertices"], mine["welded_vertices"]) == (stats["vertices"], stats["welded_vertices"])
    assert (mine["input_triangles"], mine["degenerate_triangles"]) == (
        stats["input_triangles"],
        stats["degenerate_triangles"],
    )
    assert mine["edges"] == stats["edges"]
    for name, value in mine["chamfer"].items():
        # JSON holds the f32 radii as their shortest decimal: compare them as f32 again.
        assert np.float32(value) == np.float32(stats["chamfer"][name]), name


@pytest.mark.parametrize("path", OLD_ASSETS, ids=lambda p: p.name)
def test_the_reader_reads_the_fixture_assets_of_older_versions(path):
    data = path.read_bytes()
    read = format_reader.read(data)
    assert read["version"] < 5
    assert_same(read, chamfer.load(path))


def four_cubes():
    """fixtures/shapes/two-cubes.obj and a copy beside it: two intersection polylines."""
    lines = (SHAPES / "two-cubes.obj").read_text().splitlines()
    vertices = [l for l in lines if l.startswith("v ")]
    copy = [f"v {float(l.split()[1]) + 10} {' '.join(l.split()[2:])}" for l in vertices]
    faces = [l for l in lines if l.startswith("f ")]
    moved = ["f " + " ".join(str(int(i) + len(vertices)) for i in l.split()[1:]) for l in faces]
    return "\n".join(vertices + copy + faces + moved).encode()


BAKES = [(mesh, {}) for mesh in mesh_files(MESHES)] + [
    ("four-cubes.obj", {"intersections": True}),
    (SHAPES / "cube-marked-ascii.ply", {}),
    (SHAPES / "two-materials.glb", {}),
    (MESHES / "fandisk.obj", {"radius_rel": 0.01}),
    (SHAPES / "nonmanifold-fan.obj", {}),
    (SHAPES / "open-box.obj", {}),
    (SHAPES / "cylinder-skinned.glb", {}),
    (SHAPES / "cube-morph.glb", {}),
]


@pytest.fixture(scope="module")
def baked():
    """Each bake's bytes, the reader's arrays and the asset chamfer decodes from the same bytes."""
    results = []
    for mesh, options in BAKES:
        if isinstance(mesh, str):
            data = chamfer.bake(four_cubes(), name=mesh, **options).encode()
        else:
            data, mesh = chamfer.bake(mesh, **options).encode(), mesh.name
        results.append((mesh, data, format_reader.read(data), chamfer.decode(data, mesh)))
    return results


def test_the_reader_reads_every_fresh_bake_as_chamfer_does(baked):
    for name, _, read, asset in baked:
        assert read["version"] == 6, name
        assert_same(read, asset)
        clusters = read["edge_clusters"]
        assert len(clusters) == -(-asset.edge_count // 64), name
        # The union of each run's flags, as §3.8 says.
        flags = read["edge_flags"].astype(np.uint32)
        for i in range(len(clusters)):
            assert clusters["flags"][i] == np.bitwise_or.reduce(flags[64 * i : 64 * i + 64]), name


def test_the_bakes_exercise_every_rule_of_the_reader(baked):
    """The reader is tested on each kind of content: both index widths, the render vertex counts and
    stored positions, rings and caps, several intersection polylines, radii and every flag."""
    reads = [read for _, _, read, _ in baked]
    assert {r["mesh_indices"].dtype for r in reads} == {np.dtype(np.uint16), np.dtype(np.uint32)}
    assert any(len(r["next_ends"]) and len(r["cap_heads"]) for r in reads)
    assert any(len(r["intersection_starts"]) > 1 for r in reads)
    assert any((r["edge_radii"] > 0).any() for r in reads)
    flags = np.bitwise_or.reduce([np.bitwise_or.reduce(r["edge_flags"]) for r in reads])
    assert flags == 0xFF, hex(flags)
    assert any(len(r["skin_joints"]) and r["rig"]["animations"] for r in reads), "a skinned bake"
    assert any(len(r["morph_starts"]) for r in reads), "a morph target"
    old = [format_reader.read(p.read_bytes()) for p in OLD_ASSETS]
    stored = [r for r in reads + old if r["header"]["sections"][0][2] > 0]
    assert stored, "no asset stores its render positions (§3.1)"


def test_compact_files_are_named_not_misread(baked):
    for name, _, _, asset in baked[:3]:
        with pytest.raises(format_reader.CompactFile, match="coded"):
            format_reader.read(asset.encode(compact=True))
    # The header and section table read the same in a compact file.
    data = baked[0][3].encode(compact=True)
    header = format_reader.read_header(data[16 : 16 + int.from_bytes(data[12:16], "little")])
    assert header["source"] == baked[0][3].source
    coded = {kind for kind, _, length in header["sections"] if length and kind >= 13}
    assert coded, header["sections"]


def accepted_by_chamfer(data):
    try:
        chamfer.decode(data, "damaged.chamfer")
    except chamfer.AssetError:
        return False
    return True


def accepted_by_reader(data):
    try:
        format_reader.read(data)
    except format_reader.FormatError:
        return False
    return True


@pytest.mark.parametrize(
    "path, bake",
    [(FIXTURES / "assets" / "cube-v3.chamfer", None), (None, "cube.obj"), (None, "cube-morph.glb")],
    ids=["cube-v3", "cube-v6", "cube-morph-v6"],
)
def test_the_reader_rejects_what_chamfer_rejects(path, bake, baked):
    """Every byte of a small asset changed (three ways) and every truncation: the reader and the
    Rust decoder agree on which files are assets, so the document states every rule (the morph
    cube's rig, skin-less, and morph sections included)."""
    original = path.read_bytes() if path else next(d for n, d, _, _ in baked if n == bake)
    disagreements = []
    rejected = 0
    for at in range(len(original)):
        for change in (lambda b: b ^ 0x01, lambda b: b ^ 0x80, lambda b: 0xFF):
            damaged = bytearray(original)
            damaged[at] = change(damaged[at])
            damaged = bytes(damaged)
            by_chamfer = accepted_by_chamfer(damaged)
            rejected += not by_chamfer
            if by_chamfer != accepted_by_reader(damaged):
                disagreements.append((at, damaged[at], by_chamfer))
    for length in range(len(original)):
        if accepted_by_chamfer(original[:length]) != accepted_by_reader(original[:length]):
            disagreements.append(("truncated", length))
    assert not disagreements, disagreements[:20]
    # Not a vacuous agreement: most changes break a rule, some (statistics, padding) do not.
    assert len(original) < rejected < 3 * len(original)
