"""Every kind of bad input raises its ChamferError subclass with the file named, never a crash."""

import os

import numpy as np
import pytest

import chamfer
from conftest import BROKEN, HOSTILE, MESHES, SHAPES, mesh_files

CUBE_V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float32)
CUBE_F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int64)


def raises(kind, call, named):
    """`call()` raises exactly `kind`, whose message and `path` name `named`."""
    with pytest.raises(chamfer.ChamferError) as caught:
        call()
    error = caught.value
    assert type(error) is kind, f"{type(error).__name__}: {error}"
    assert str(named) in str(error), str(error)
    if error.path is not None:
        assert str(named) in error.path
    return error


@pytest.mark.parametrize(
    "name, kind",
    [
        ("truncated.ply", chamfer.FormatError),
        ("wrong-header.ply", chamfer.FormatError),
        ("truncated.glb", chamfer.FormatError),
        ("bad-index.gltf", chamfer.FormatError),
        ("draco-required.gltf", chamfer.UnsupportedError),
        ("nan-position.obj", chamfer.FormatError),  # refused at its line by the OBJ reader
        ("index-out-of-range.obj", chamfer.FormatError),  # tobj refuses it while parsing
        ("all-degenerate.obj", chamfer.MeshError),
        ("empty.obj", chamfer.MeshError),
    ],
)
def test_broken_files_raise_their_kind(name, kind):
    path = BROKEN / name
    error = raises(kind, lambda: chamfer.bake(path), path)
    assert error.path == str(path)
    # Their bytes fail the same way.
    raises(kind, lambda: chamfer.bake(path.read_bytes(), name=name), name)


def test_unsupported_is_a_format_error():
    assert issubclass(chamfer.UnsupportedError, chamfer.FormatError)


def test_missing_and_special_files_are_read_errors(tmp_path):
    raises(chamfer.ReadError, lambda: chamfer.bake(tmp_path / "missing.obj"), "missing.obj")
    folder = tmp_path / "folder.obj"
    folder.mkdir()
    raises(chamfer.ReadError, lambda: chamfer.bake(folder), "folder.obj")
    fifo = tmp_path / "pipe.ply"
    os.mkfifo(fifo)
    raises(chamfer.ReadError, lambda: chamfer.bake(fifo), "pipe.ply")  # refused, not a hang
    raises(chamfer.ReadError, lambda: chamfer.load(tmp_path / "missing.chamfer"), "missing.chamfer")
    raises(chamfer.FormatError, lambda: chamfer.bake(SHAPES / "two-materials.bin"), "two-materials.bin")


@pytest.mark.parametrize("path", mesh_files(HOSTILE), ids=lambda p: p.name)
def test_hostile_files_end_in_an_exception_or_an_asset(path):
    try:
        asset = chamfer.bake(path)
    except chamfer.ChamferError as error:
        assert path.name in str(error)
    else:
        assert asset.source == path.name


def test_limits_refuse_big_files_with_the_file_named():
    fandisk = MESHES / "fandisk.obj"
    raises(chamfer.LimitError, lambda: chamfer.bake(fandisk, max_triangles=100), fandisk)
    raises(chamfer.LimitError, lambda: chamfer.bake(fandisk, max_vertices=100), fandisk)
    raises(chamfer.LimitError, lambda: chamfer.bake(fandisk, max_input_bytes=1000), fandisk)
    data = (MESHES / "bunny-loop2.ply.gz").read_bytes()
    # A small .gz that inflates past the limit stops at the limit.
    raises(chamfer.LimitError, lambda: chamfer.bake(data, name="b.ply.gz", max_input_bytes=len(data) + 10), "b.ply.gz")
    raises(chamfer.LimitError, lambda: chamfer.bake_arrays(CUBE_V, CUBE_F, name="tet", max_vertices=3), "tet")
    raises(chamfer.LimitError, lambda: chamfer.bake_arrays(CUBE_V, CUBE_F, name="tet", max_triangles=3), "tet")


@pytest.mark.parametrize(
    "options",
    [
        {"crease_deg": -1.0},
        {"crease_deg": float("nan")},
        {"crease_deg": 200},
        {"coplanar_deg": 50.0},
        {"crease_deg": "30"},
        {"crease_deg": True},
        {"intersections": 1},
        {"intersections": "no"},
        {"max_triangles": -5},
        {"max_triangles": 2.5},
        {"max_triangles": 1 << 70},
        {"radius": 0.0},
        {"radius_rel": 2.0},
        {"weld_rel": 0.5},
        {"weld_epsilon": float("inf")},
        {"radius": 0.1, "radius_rel": 0.01},
        {"weld_epsilon": 0.0, "weld_rel": 1e-6},
        {"crease": 30},
    ],
    ids=repr,
)
def test_wrong_options_are_options_errors(options):
    bad = next(iter(options))
    for call in [
        lambda: chamfer.bake(SHAPES / "cube.obj", **options),
        lambda: chamfer.bake_arrays(CUBE_V, CUBE_F, **options),
        lambda: chamfer.settings(**options),
    ]:
        with pytest.raises(chamfer.OptionsError) as caught:
            call()
        assert bad.replace("_", "-") in str(caught.value) or bad in str(caught.value)


def test_none_leaves_an_option_at_its_default():
    assert chamfer.bake(SHAPES / "cube.obj", radius=None, crease_deg=None).encode() == chamfer.bake(SHAPES / "cube.obj").encode()


@pytest.mark.parametrize(
    "vertices, faces, needle",
    [
        (CUBE_V.astype(np.int32), CUBE_F, "float32 or float64"),
        (CUBE_V[:, :2], CUBE_F, "shape (N, 3)"),
        (CUBE_V.ravel(), CUBE_F, "shape (N, 3)"),
        (CUBE_V, CUBE_F.astype(np.float64), "integers"),
        (CUBE_V, CUBE_F[:, :2], "shape (N, 3)"),
        (CUBE_V, CUBE_F - 1, "index -1"),
        (CUBE_V, CUBE_F + (1 << 40), "no vertex number"),
        ([["a", "b", "c"]], CUBE_F, "float32 or float64"),
        (CUBE_V.astype(np.complex64), CUBE_F, "float32 or float64"),
    ],
)
def test_wrong_arrays_are_array_errors(vertices, faces, needle):
    error = raises(chamfer.ArrayError, lambda: chamfer.bake_arrays(vertices, faces, name="part-7"), "part-7")
    assert needle in str(error)


def test_arrays_that_are_no_mesh_are_mesh_errors():
    nan = CUBE_V.copy()
    nan[2, 1] = np.nan
    raises(chamfer.MeshError, lambda: chamfer.bake_arrays(nan, CUBE_F, name="nan-part"), "nan-part")
    raises(chamfer.MeshError, lambda: chamfer.bake_arrays(CUBE_V, CUBE_F + 1, name="past-the-end"), "past-the-end")
    raises(chamfer.MeshError, lambda: chamfer.bake_arrays(CUBE_V, CUBE_F[:0], name="no-faces"), "no-faces")
    huge = CUBE_V.astype(np.float64) * 1e300  # beyond float32: infinite
    raises(chamfer.MeshError, lambda: chamfer.bake_arrays(huge, CUBE_F, name="huge"), "huge")
    raises(chamfer.ArrayError, lambda: chamfer.from_trimesh(object(), name="thing"), "thing")


def test_bad_assets_are_asset_errors(tmp_path):
    good = chamfer.bake(SHAPES / "cube.obj").encode()
    cases = {
        "text.chamfer": b"not an asset at all",
        "truncated.chamfer": good[: len(good) // 2],
        "version.chamfer": good[:8] + (99).to_bytes(4, "little") + good[12:],
        "trailing.chamfer": good + b"\0" * 16,
        "empty.chamfer": b"",
    }
    for name, data in cases.items():
        path = tmp_path / name
        path.write_bytes(data)
        raises(chamfer.AssetError, lambda: chamfer.load(path), name)
        raises(chamfer.AssetError, lambda: chamfer.decode(data, name=name), name)


def test_outputs_that_cannot_be_written_are_write_errors(tmp_path):
    asset = chamfer.bake(SHAPES / "cube.obj")
    raises(chamfer.WriteError, lambda: asset.save(tmp_path), tmp_path)
    fifo = tmp_path / "out.chamfer"
    os.mkfifo(fifo)
    raises(chamfer.WriteError, lambda: asset.save(fifo), "out.chamfer")
    raises(chamfer.WriteError, lambda: asset.save(tmp_path / "no" / "such" / "dir.chamfer"), "dir.chamfer")
    ply = tmp_path / "cube.ply"
    ply.write_bytes((SHAPES / "cube-marked-ascii.ply").read_bytes())
    before = ply.read_bytes()
    raises(chamfer.WriteError, lambda: chamfer.annotate(ply, ply), "cube.ply")
    assert ply.read_bytes() == before  # the input is never touched
    raises(chamfer.WriteError, lambda: chamfer.draw_svg(ply, ply), "cube.ply")
    assert ply.read_bytes() == before


def test_wrong_draw_and_annotate_arguments_are_options_errors(tmp_path):
    asset = chamfer.bake(SHAPES / "cube.obj")
    for kwargs in [{"width": 0}, {"height": 20000}, {"azimuth": float("nan")}, {"distance": -1.0},
                   {"elevation": 91.0}, {"fov_y": 0.5}, {"ortho": 1}, {"zoom": 2.0},
                   {"classes": ["contour", "outlines"]}, {"scale": 0.0}]:
        with pytest.raises(chamfer.OptionsError):
            chamfer.draw_svg(asset, **kwargs)
    with pytest.raises(chamfer.OptionsError):
        chamfer.annotate(SHAPES / "cube-marked-ascii.ply", tmp_path / "a.ply", gltf_edges=["bogus"])
    with pytest.raises(chamfer.OptionsError):
        chamfer.bake(b"v 0 0 0\n")  # bytes without a name
    with pytest.raises(TypeError):
        chamfer.bake(42)
