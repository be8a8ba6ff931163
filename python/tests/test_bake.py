"""Bakes from Python equal the `chamfer` command's, byte for byte; stats equal `inspect --json`;
arrays, bytes and trimesh meshes give the same edges as files; the section views share memory."""

import gc
import gzip
import pickle

import numpy as np
import pytest

import chamfer
from conftest import MESHES, SHAPES, mesh_files

# Non-default options, each with its `chamfer bake` flags.
OPTION_SETS = [
    ({}, []),
    ({"crease_deg": 40.0, "radius_rel": 0.005}, ["--crease-deg", "40", "--radius-rel", "0.005"]),
    (
        {"weld_epsilon": 0.0, "coplanar_deg": 1.0, "radius": 0.02, "radius_valleys": True},
        ["--weld-epsilon", "0", "--coplanar-deg", "1", "--radius", "0.02", "--radius-valleys"],
    ),
    ({"intersections": True, "weld_rel": 1e-4}, ["--intersections", "--weld-rel", "0.0001"]),
]


@pytest.fixture(scope="module")
def cli_bakes(cli, tmp_path_factory):
    """Every bundled mesh (fixtures/meshes) baked by the command with default options, at once."""
    out = tmp_path_factory.mktemp("cli")
    cli.run("bake", MESHES, "-o", out)
    return out


@pytest.mark.parametrize("mesh", mesh_files(MESHES), ids=lambda p: p.name)
def test_every_bundled_mesh_bakes_to_the_cli_bytes_and_stats(mesh, cli, cli_bakes):
    expected = cli_bakes / (mesh.name.split(".")[0] + ".chamfer")
    asset = chamfer.bake(mesh)
    assert asset.encode() == expected.read_bytes()
    report = cli.inspect(expected)
    assert asset.stats == report
    assert chamfer.load(expected).stats == report


@pytest.mark.parametrize("flags", OPTION_SETS, ids=lambda o: " ".join(o[1]) or "defaults")
@pytest.mark.parametrize(
    "mesh",
    [SHAPES / "cube-marked-ascii.ply", SHAPES / "two-materials.glb", SHAPES / "cylinder-16.obj", MESHES / "fandisk.obj"],
    ids=lambda p: p.name,
)
def test_options_give_what_the_same_flags_give(mesh, flags, cli, tmp_path):
    options, cli_flags = flags
    expected = cli.bake(mesh, tmp_path / "cli.chamfer", *cli_flags)
    asset = chamfer.bake(mesh, **options)
    assert asset.encode() == expected
    assert asset.stats == cli.inspect(tmp_path / "cli.chamfer")
    # The asset's settings are the options' plus the bake's record of where stitching started.
    recorded = dict(asset.settings)
    assert int(recorded.pop("stitch_boundary_before")) >= 0
    assert dict(chamfer.settings(**options)) == recorded


def test_bytes_bake_as_the_file_does(tmp_path):
    for mesh in [SHAPES / "cube-marked-le.ply", SHAPES / "cube-marked-extras.glb", MESHES / "suzanne.obj"]:
        from_file = chamfer.bake(mesh).encode()
        assert chamfer.bake(mesh.read_bytes(), name=mesh.name).encode() == from_file
    # Compressed bytes are inflated, as a .ply.gz file is.
    ply = (SHAPES / "cube-marked-le.ply").read_bytes()
    gz = gzip.compress(ply, mtime=0)
    (tmp_path / "cube.ply.gz").write_bytes(gz)
    assert chamfer.bake(gz, name="cube.ply.gz").encode() == chamfer.bake(tmp_path / "cube.ply.gz").encode()


def edge_set(asset):
    """The edges by their end points' positions (independent of vertex numbering) and classes."""
    positions = asset.topology_positions
    ends = asset.edge_vertices[:, :2]
    return sorted(
        (tuple(sorted((tuple(positions[a]), tuple(positions[b])))), int(flags))
        for (a, b), flags in zip(ends, asset.edge_flags)
    )


@pytest.mark.parametrize("name", ["fandisk.obj", "cow.obj", "teapot.obj", "suzanne.obj", "cylinder-trimesh-32.obj"])
def test_trimesh_arrays_give_the_edges_of_the_file(name):
    trimesh = pytest.importorskip("trimesh")
    # Without materials: textured ones would need Pillow, and the edges do not depend on them.
    mesh = trimesh.load(MESHES / name, force="mesh", skip_materials=True)
    from_arrays = chamfer.bake_arrays(mesh.vertices, mesh.faces, name=name)
    from_file = chamfer.bake(MESHES / name)
    assert from_arrays.edge_count == from_file.edge_count
    assert edge_set(from_arrays) == edge_set(from_file)
    assert from_arrays.stats["edges"] == from_file.stats["edges"]
    via_helper = chamfer.from_trimesh(mesh)
    assert via_helper.source == name
    assert via_helper.encode() == from_arrays.encode()


def test_bake_arrays_takes_any_float_and_integer_widths():
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
    f = np.array([[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
                  [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]])
    reference = chamfer.bake_arrays(v, f, name="cube").encode()
    for vertices in [v.astype(np.float32), v.astype(np.float64), np.asfortranarray(v), v.tolist()]:
        for faces in [f.astype(t) for t in (np.int32, np.int64, np.uint32, np.uint16, np.uint8)]:
            assert chamfer.bake_arrays(vertices, faces, name="cube").encode() == reference
    cube = chamfer.bake_arrays(v, f, name="cube")
    assert cube.edge_count == 12
    assert all(flag & chamfer.EdgeFlags.RIDGE for flag in cube.edge_flags)


def test_sections_are_read_only_views_of_the_asset():
    asset = chamfer.bake(MESHES / "fandisk.obj", radius_rel=0.01)
    vertices = asset.edge_vertices
    assert vertices.base is asset
    assert vertices.shape == (asset.edge_count, 4)
    assert vertices.dtype == np.uint16  # fandisk's 6.5 k vertices fit 16 bits, as in the file
    # The same memory every time: no copy is made.
    assert asset.edge_vertices.ctypes.data == vertices.ctypes.data
    assert not vertices.flags.writeable
    with pytest.raises(ValueError):
        vertices[0, 0] = 1
    with pytest.raises(ValueError):
        vertices.flags.writeable = True
    # The flags are the low halves of the attribute words, viewed in place.
    flags = asset.edge_flags
    assert flags.strides == (4,)
    assert np.array_equal(flags, asset.edge_attributes & 0xFFFF)
    assert flags.ctypes.data == asset.edge_attributes.ctypes.data
    chamfer_edges = (flags & chamfer.EdgeFlags.CHAMFER) != 0
    assert chamfer_edges.any()
    assert (asset.edge_radii[chamfer_edges] > 0).all() and (asset.edge_radii[~chamfer_edges] == 0).all()
    assert asset.render_positions.shape == asset.render_normals.shape == (asset.stats["render_vertices"], 3)
    assert asset.mesh_indices.shape == (asset.triangle_count, 3)
    assert asset.topology_positions.shape == (asset.stats["welded_vertices"], 3)
    assert asset.next_ends.shape == (2 * asset.edge_count,)
    assert asset.cap_heads.shape == (asset.stats["caps"],)
    # A view outlives the last other reference to its asset.
    expected = vertices.copy()
    del asset
    gc.collect()
    assert np.array_equal(vertices, expected)


def test_intersections_are_arrays_too():
    asset = chamfer.bake(SHAPES / "two-materials.glb", intersections=True)
    segments, starts = asset.intersection_segments, asset.intersection_starts
    assert segments.shape == (asset.stats["intersections"]["segments"], 2, 3)
    assert starts.shape == (asset.stats["intersections"]["polylines"],)


def test_save_load_pickle_and_decode_round_trip(tmp_path):
    asset = chamfer.bake(MESHES / "cube.obj")
    path = tmp_path / "cube.chamfer"
    asset.save(path)
    assert path.read_bytes() == asset.encode()
    assert [p.name for p in tmp_path.iterdir()] == ["cube.chamfer"]  # no temporary file left
    loaded = chamfer.load(path)
    assert loaded.encode() == asset.encode() and loaded.stats == asset.stats
    again = pickle.loads(pickle.dumps(asset))
    assert again.encode() == asset.encode()
    assert chamfer.decode(asset.encode()).edge_count == asset.edge_count
    # Saving over a file replaces it.
    chamfer.bake(MESHES / "suzanne.obj").save(path)
    assert chamfer.load(path).source == "suzanne.obj"


def test_help_is_useful():
    doc = chamfer.bake.__doc__
    for name, _, _ in chamfer.OPTIONS:
        assert name in doc, name
    for needle in ["ReadError", "FormatError", "MeshError", "LimitError", "released", "name"]:
        assert needle in doc
    assert chamfer.bake.__text_signature__ == "(source, *, name=None, **options)"
    # The keyword lists are the schemas' (issue 40): every entry with its help, for bake and draw_svg.
    flat = lambda text: " ".join(text.split())
    for function, schemas in [(chamfer.bake, [chamfer.BAKE_SCHEMA]),
                              (chamfer.draw_svg, [chamfer.VIEW_SCHEMA, chamfer.BAKE_SCHEMA])]:
        for entry in (e for schema in schemas for e in schema if e["group"] in ("bake", "view")):
            assert f"{entry['name']}: " in function.__doc__, (function, entry["name"])
            assert flat(entry["help"]) in flat(function.__doc__), (function, entry["name"])
    assert "{" not in chamfer.bake.__doc__ + chamfer.draw_svg.__doc__
    for function in [chamfer.bake_arrays, chamfer.load, chamfer.draw_svg, chamfer.annotate, chamfer.from_trimesh]:
        assert len(function.__doc__) > 100, function
    assert "numpy" in chamfer.Asset.__doc__
    assert isinstance(chamfer.ReadError("x"), chamfer.ChamferError)


def test_the_stubs_name_what_the_module_has():
    import ast
    from pathlib import Path

    stub = ast.parse((Path(chamfer._chamfer.__file__).parent / "_chamfer.pyi").read_text())
    names = set()
    for node in stub.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
    public = {n for n in dir(chamfer._chamfer) if not n.startswith("_") or n == "__version__"}
    assert public == names - {"BakeOptions", "EncodingOptions", "ViewOptions", "SectionOptions",
                              "DrawingStyleOptions", "DrawOptions"}
    options = next(n for n in stub.body if isinstance(n, ast.ClassDef) and n.name == "BakeOptions")
    # The TypedDict is the schema's bake group: same names, order and types.
    keys = [(s.target.id, ast.unparse(s.annotation)) for s in options.body if isinstance(s, ast.AnnAssign)]
    assert keys == [(name, f"Optional[{kind}]") for name, kind, _ in chamfer.OPTIONS]
    # Asset.encode's and save's keywords are the schema's encoding group.
    encoding = next(n for n in stub.body if isinstance(n, ast.ClassDef) and n.name == "EncodingOptions")
    keys = [(s.target.id, ast.unparse(s.annotation)) for s in encoding.body if isinstance(s, ast.AnnAssign)]
    kinds = {"number": "float", "count": "int", "flag": "bool"}
    assert keys == [(e["name"], f"Optional[{kinds[e['kind']]}]") for e in chamfer.BAKE_SCHEMA if e["group"] == "encoding"]
    # And the view's TypedDict is the view schema.
    view = next(n for n in stub.body if isinstance(n, ast.ClassDef) and n.name == "ViewOptions")
    keys = [(s.target.id, ast.unparse(s.annotation)) for s in view.body if isinstance(s, ast.AnnAssign)]
    kinds = {"number": "float", "count": "int", "flag": "bool"}
    assert keys == [(e["name"], f"Optional[{kinds[e['kind']]}]") for e in chamfer.VIEW_SCHEMA]
    # And the section's and the line styles' are their schemas.
    kinds["numbers"] = "Sequence[float]"
    for stub_name, schema in [("SectionOptions", chamfer.SECTION_SCHEMA),
                              ("DrawingStyleOptions", chamfer.DRAWING_STYLE_SCHEMA)]:
        typed = next(n for n in stub.body if isinstance(n, ast.ClassDef) and n.name == stub_name)
        keys = [(s.target.id, ast.unparse(s.annotation)) for s in typed.body if isinstance(s, ast.AnnAssign)]
        assert keys == [(e["name"], f"Optional[{kinds[e['kind']]}]") for e in schema], stub_name
    assert (Path(chamfer.__file__).parent / "py.typed").is_file()


def test_compact_files_are_the_cli_compact_bakes_and_state_their_precision(cli, tmp_path):
    mesh = MESHES / "fandisk.obj"
    expected = cli.bake(mesh, tmp_path / "cli.chamfer", "--compact")
    asset = chamfer.bake(mesh)
    assert asset.encode(compact=True) == expected
    asset.save(tmp_path / "py.chamfer", compact=True)
    assert (tmp_path / "py.chamfer").read_bytes() == expected
    loaded = chamfer.load(tmp_path / "py.chamfer")
    assert loaded.stats == cli.inspect(tmp_path / "cli.chamfer")
    assert loaded.stats["precision"]["position_bits"] == 16
    assert loaded.stats["bytes"]["total"] == len(expected) < len(asset.encode())
    # Same indices and edges; positions within the stated bound.
    assert np.array_equal(loaded.edge_vertices, asset.edge_vertices)
    error = loaded.stats["precision"]["position_error"]
    assert np.abs(loaded.topology_positions - asset.topology_positions).max() <= error
    lossless = chamfer.decode(asset.encode(compact=True, position_bits=32, normal_bits=32))
    assert np.array_equal(lossless.topology_positions, asset.topology_positions)
    with pytest.raises(chamfer.OptionsError, match="position_bits needs option compact"):
        asset.encode(position_bits=12)
    with pytest.raises(chamfer.OptionsError, match='unknown option "weld_rel"'):
        asset.encode(compact=True, weld_rel=0.1)
    with pytest.raises(chamfer.OptionsError, match="position bits"):
        asset.save(tmp_path / "never.chamfer", compact=True, position_bits=20)
    assert not (tmp_path / "never.chamfer").exists()


def test_every_schema_option_is_a_keyword_that_bakes_what_chamfer_bake_bakes(cli, tmp_path):
    """Issue 40: each entry of the bake schema, set to its example through Python's keywords (the
    "bake" group: bake(); "encoding": Asset.encode()), bakes chamfer bake's bytes with its flag."""
    mesh = MESHES / "fandisk.obj"
    schema = {e["name"]: e for e in chamfer.BAKE_SCHEMA}
    assert [e["name"] for e in chamfer.BAKE_SCHEMA if e["group"] == "bake"] == [n for n, _, _ in chamfer.OPTIONS]
    for entry in chamfer.BAKE_SCHEMA:
        given = [schema[name] for name in [*entry["requires"], entry["name"]]]
        assert all(e["example"] is not None and e["example"] != e["default"] for e in given), given
        flags = []
        for e in given:
            flags += ["--" + e["name"].replace("_", "-")] + ([] if e["kind"] == "flag" else [str(e["example"])])
        expected = cli.bake(mesh, tmp_path / f"{entry['name']}.chamfer", *flags)
        bake = {e["name"]: e["example"] for e in given if e["group"] == "bake"}
        encode = {e["name"]: e["example"] for e in given if e["group"] == "encoding"}
        assert chamfer.bake(mesh, **bake).encode(**encode) == expected, flags
