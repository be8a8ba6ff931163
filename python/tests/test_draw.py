"""draw_svg and annotate give what `chamfer draw` and `chamfer annotate` write, byte for byte."""

import pytest

import chamfer
from conftest import MESHES, SHAPES

CAMERAS = [
    ({}, []),
    ({"azimuth": -120.0, "elevation": 30.0, "distance": 11.5, "hidden": True},
     ["--azimuth", "-120", "--elevation", "30", "--distance", "11.5", "--hidden"]),
    ({"width": 640, "height": 640, "azimuth": 0.0, "elevation": 90.0, "ortho": True, "scale": 20.0,
      "classes": ["contour", "crease"]},
     ["--width", "640", "--height", "640", "--azimuth", "0", "--elevation", "90", "--ortho", "--scale", "20",
      "--classes", "contour,crease"]),
]


@pytest.mark.parametrize("camera", CAMERAS, ids=lambda c: " ".join(c[1]) or "defaults")
@pytest.mark.parametrize("mesh", [MESHES / "fandisk.obj", SHAPES / "two-cubes.obj"], ids=lambda p: p.name)
def test_drawings_equal_the_cli_s(mesh, camera, cli, tmp_path):
    kwargs, flags = camera
    cli.run("draw", mesh, "-o", tmp_path / "cli.svg", *flags)
    expected = (tmp_path / "cli.svg").read_text()
    assert chamfer.draw_svg(mesh, tmp_path / "py.svg", **kwargs) == expected
    assert (tmp_path / "py.svg").read_text() == expected
    # From the asset, baked as `chamfer draw` bakes a mesh (with intersections), titled the same.
    asset = chamfer.bake(mesh, intersections=True)
    assert chamfer.draw_svg(asset, title=mesh.name, **kwargs) == expected


def test_every_view_schema_entry_is_a_keyword_that_draws_what_chamfer_draw_draws(cli, tmp_path):
    """Issue 40: each entry of the view schema, set to its example as a keyword, draws what its
    flag draws, and changes the drawing (so the value arrives)."""
    mesh = MESHES / "fandisk.obj"
    assert [e["name"] for e in chamfer.VIEW_SCHEMA] == ["azimuth", "elevation", "distance", "fov_y", "ortho"]
    default = chamfer.draw_svg(mesh)
    for entry in chamfer.VIEW_SCHEMA:
        assert entry["group"] == "view" and entry["example"] != entry["default"], entry
        flag = "--" + entry["name"].replace("_", "-")
        flags = [flag] if entry["kind"] == "flag" else [flag, str(entry["example"])]
        cli.run("draw", mesh, "-o", tmp_path / "cli.svg", *flags)
        drawn = chamfer.draw_svg(mesh, **{entry["name"]: entry["example"]})
        assert drawn == (tmp_path / "cli.svg").read_text(), entry["name"]
        assert drawn != default, entry["name"]


def test_a_chamfer_file_draws_as_the_cli_draws_it(cli, tmp_path):
    asset_path = tmp_path / "fandisk.chamfer"
    chamfer.bake(MESHES / "fandisk.obj", radius_rel=0.01).save(asset_path)
    cli.run("draw", asset_path, "-o", tmp_path / "cli.svg", "--hidden")
    assert chamfer.draw_svg(asset_path, hidden=True) == (tmp_path / "cli.svg").read_text()


@pytest.mark.parametrize(
    "mesh, output, kwargs, flags",
    [
        (SHAPES / "cube-marked-ascii.ply", "out.ply", {"radius_rel": 0.01}, ["--radius-rel", "0.01"]),
        (SHAPES / "two-materials.glb", "out.glb",
         {"gltf_edges": ["extras", "edge-visibility", "outline"]}, ["--gltf-edges", "extras,edge-visibility,outline"]),
        (MESHES / "cube.obj", "out.gltf", {"radius": 0.05}, ["--radius", "0.05"]),
    ],
    ids=lambda v: v.name if hasattr(v, "name") else None,
)
def test_annotate_writes_what_the_cli_writes(mesh, output, kwargs, flags, cli, tmp_path):
    (tmp_path / "cli").mkdir()
    (tmp_path / "py").mkdir()
    cli.run("annotate", mesh, "-o", tmp_path / "cli" / output, *flags)
    report = chamfer.annotate(mesh, tmp_path / "py" / output, **kwargs)
    assert report["edges"] + report["hard_edges"] > 0
    for written in (tmp_path / "cli").iterdir():
        assert (tmp_path / "py" / written.name).read_bytes() == written.read_bytes(), written.name
