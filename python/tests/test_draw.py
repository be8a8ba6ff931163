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


SECTION = ({"section": [1.0, 0.0, 0.0, 0.5], "azimuth": 90.0, "elevation": 0.0, "ortho": True, "hidden": True,
            "scale": 50.0, "cut_color": (1.0, 0.0, 0.0), "hidden_dash": [1.0, 2.0]},
           ["--section", "1,0,0,0.5", "--azimuth", "90", "--elevation", "0", "--ortho", "--hidden", "--scale", "50",
            "--cut-color", "1,0,0", "--hidden-dash", "1,2"])


@pytest.mark.parametrize("suffix, draw", [("svg", "draw_svg"), ("pdf", "draw_pdf"), ("dxf", "draw_dxf")])
def test_section_drawings_equal_the_cli_s_in_every_format(suffix, draw, cli, tmp_path):
    """Issue 43: draw_svg/pdf/dxf(section=...) give what `chamfer draw --section` writes."""
    kwargs, flags = SECTION
    mesh = SHAPES / "cube.obj"
    cli.run("draw", mesh, "-o", tmp_path / f"cli.{suffix}", *flags)
    expected = (tmp_path / f"cli.{suffix}").read_bytes()
    drawn = getattr(chamfer, draw)(mesh, tmp_path / f"py.{suffix}", **kwargs)
    assert (drawn if isinstance(drawn, bytes) else drawn.encode()) == expected
    assert (tmp_path / f"py.{suffix}").read_bytes() == expected


def test_the_dxf_reads_back_with_its_layers_units_and_entities(tmp_path):
    """The DXF, read by ezdxf: millimetres, a layer per role with the role's line type, the cut
    outline one closed LWPOLYLINE around the 50 mm square, the hatch on its own layer."""
    import ezdxf
    kwargs, _ = SECTION
    path = tmp_path / "cube.dxf"
    chamfer.draw_dxf(SHAPES / "cube.obj", path, **kwargs)
    doc = ezdxf.readfile(path)
    assert doc.header["$INSUNITS"] == 4
    layers = {layer.dxf.name for layer in doc.layers}
    assert {"cut", "hatch", "hidden"} <= layers
    assert doc.layers.get("hidden").dxf.linetype == "CHAMFER_HIDDEN"
    tags = doc.linetypes.get("CHAMFER_HIDDEN").pattern_tags.tags
    pattern = [tag.value for tag in tags if tag.code in (40, 49)]  # total length, then dash, -gap
    assert [round(x, 6) for x in pattern] == [3.0, 1.0, -2.0]
    entities = list(doc.modelspace())
    assert all(e.dxftype() == "LWPOLYLINE" for e in entities)
    by_layer = {}
    for e in entities:
        by_layer.setdefault(e.dxf.layer, []).append(e)
    assert len(by_layer["cut"]) == 1
    cut = by_layer["cut"][0]
    assert cut.closed and cut.dxf.lineweight == 70 and cut.rgb == (255, 0, 0)
    xs, ys = zip(*[(x, y) for x, y, *_ in cut.get_points()])
    assert max(xs) - min(xs) == pytest.approx(50.0, abs=0.01)
    assert max(ys) - min(ys) == pytest.approx(50.0, abs=0.01)
    # 2 mm hatch at 45 degrees across a 50 mm square: its diagonal over the spacing.
    assert abs(len(by_layer["hatch"]) - 50 * 2 ** 0.5 / 2) <= 1
    assert not set(by_layer) - {"cut", "hatch", "hidden", "silhouette", "visible", "boundary"}


def test_bad_sections_and_styles_raise_options_errors(tmp_path):
    mesh = SHAPES / "cube.obj"
    for kwargs, message in [
        ({"section": [1.0, 0.0, 0.0]}, "section must be 1 to 6 planes"),
        ({"section": "1,0,0,0"}, "section must be a sequence of numbers"),
        ({"section": [0.0, 0.0, 0.0, 1.0]}, "non-zero normal"),
        ({"section": [1.0, 0, 0, 0, 0, 1.0, 0, 0]}, "one section plane"),
        ({"section_box": [0, 0, 0, 1, 1, 1]}, "not a box"),
        ({"cut_color": [1.0, 0.0]}, "cut_color must be three numbers"),
        ({"hidden_dash": [1.0]}, "hidden_dash must be dash,gap pairs"),
        ({"hatch_spacing": -1.0}, "hatch_spacing must be 0 to 1000"),
        ({"cut_weight": float("nan")}, "cut_weight"),
        ({"section": [1.0] * 25}, "at most 24 numbers"),
    ]:
        with pytest.raises(chamfer.OptionsError, match=message):
            chamfer.draw_pdf(mesh, tmp_path / "never.pdf", **kwargs)
    assert not (tmp_path / "never.pdf").exists()


def test_every_section_and_style_entry_is_a_keyword_that_draws_what_chamfer_draw_draws(cli, tmp_path):
    """Issue 43 on the schema of issue 40: each entry of the section and line style schemas, set
    to its example, draws what its flag draws, and changes the drawing."""
    mesh = SHAPES / "cube.obj"
    base = {"section": [1.0, 0.0, 0.0, 0.5], "hidden": True}
    base_flags = ["--section", "1,0,0,0.5", "--hidden"]
    default = chamfer.draw_svg(mesh, **base)
    entries = [e for e in chamfer.SECTION_SCHEMA if e["name"] == "section"] + list(chamfer.DRAWING_STYLE_SCHEMA)
    for entry in entries:
        assert entry["example"] != entry["default"], entry
        example = entry["example"]
        if entry["name"] == "section":
            example = [1.0, 0.0, 0.0, 0.25]
        flag = "--" + entry["name"].replace("_", "-")
        text = ",".join(f"{x:g}" for x in example) if isinstance(example, list) else str(example)
        flags = base_flags[2:] + ([] if entry["name"] == "section" else base_flags[:2])
        cli.run("draw", mesh, "-o", tmp_path / "cli.svg", *flags, flag, text)
        kwargs = dict(base, **{entry["name"]: example})
        drawn = chamfer.draw_svg(mesh, **kwargs)
        assert drawn == (tmp_path / "cli.svg").read_text(), entry["name"]
        # Styles of roles this cut has no line of (boundary, intersection) change only the
        # style block; every entry changes the document.
        assert drawn != default, entry["name"]


def test_a_scale_ratio_is_the_scale_in_millimetres_of_the_model_unit(cli, tmp_path):
    """`--scale 1:50 --units m` is 20 mm per model unit, in the CLI and in Python."""
    mesh = SHAPES / "cube.obj"
    cli.run("draw", mesh, "-o", tmp_path / "ratio.svg", "--scale", "1:50", "--units", "m")
    cli.run("draw", mesh, "-o", tmp_path / "mm.svg", "--scale", "20")
    expected = (tmp_path / "mm.svg").read_text()
    assert (tmp_path / "ratio.svg").read_text() == expected
    assert chamfer.draw_svg(mesh, scale="1:50", units="m") == expected
    assert chamfer.draw_svg(mesh, scale=20) == expected
    assert chamfer.draw_svg(mesh, scale="2:5", units="cm") == chamfer.draw_svg(mesh, scale=4.0)
    for scale, units, message in [("1:0", "mm", "scale"), (-2.0, "mm", "scale"), (True, "mm", "scale"),
                                  ("1:50", "yd", "unknown unit"), (20.0, "m", "units applies to a scale ratio")]:
        with pytest.raises(chamfer.OptionsError, match=message):
            chamfer.draw_svg(mesh, scale=scale, units=units)
    # The function says the format: a mismatched extension is refused, nothing written.
    with pytest.raises(chamfer.OptionsError, match=r"draw_svg\(\) writes .svg, not .pdf"):
        chamfer.draw_svg(mesh, tmp_path / "drawing.pdf")
    assert not (tmp_path / "drawing.pdf").exists()
