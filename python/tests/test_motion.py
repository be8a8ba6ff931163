"""Animated assets from Python (issue 41): the skin and morph sections as arrays, the rig, and
`chamfer.pose` against the skinning formula computed here in float64, and against `chamfer render`'s
animation schema."""

import numpy as np
import pytest

import chamfer
from conftest import SHAPES

CYLINDER = SHAPES / "cylinder-skinned.glb"
CUBE = SHAPES / "cube-morph.glb"


def bent(vertices, angle):
    """The generator's skinning formula (tests/rigged.rs): bone 1 at (0, 1, 0) turned about z,
    weights blending linearly from y = 0.75 to 1.25."""
    w = np.clip((vertices[:, 1] - 0.75) / 0.5, 0.0, 1.0)[:, None]
    s, c = np.sin(angle), np.cos(angle)
    x, y = vertices[:, 0], vertices[:, 1] - 1.0
    turned = np.stack([c * x - s * y, s * x + c * y + 1.0, vertices[:, 2]], axis=1)
    return (1.0 - w) * vertices + w * turned


def test_the_skin_sections_and_the_rig_are_exposed():
    asset = chamfer.bake(CYLINDER)
    vertices = len(asset.topology_positions)
    assert asset.joints.shape == (vertices, 4) and asset.joints.dtype == np.uint16
    assert asset.weights.shape == (vertices, 4) and asset.weights.dtype == np.float32
    np.testing.assert_allclose(asset.weights.sum(axis=1), 1.0, atol=1e-6)
    assert asset.rig["joints"] == 2
    assert asset.rig["animations"] == [{"name": "bend", "duration": 1.0, "channels": 1}]
    assert [e["name"] for e in chamfer.ANIMATION_SCHEMA] == ["animation", "time", "pose"]
    cube = chamfer.bake(CUBE)
    assert cube.joints.shape == (0, 4)
    assert cube.rig["morph_targets"] == ["rise"]
    assert cube.morph_starts.tolist() == [0]
    assert len(cube.morph_vertices) == 4
    np.testing.assert_array_equal(cube.morph_deltas, [[0.0, 0.5, 0.0]] * 4)


def test_pose_follows_the_skinning_formula():
    asset = chamfer.bake(CYLINDER)
    rest = asset.topology_positions.astype(np.float64)
    for time, angle in [(0.0, 0.0), (0.5, np.pi / 4), (1.0, np.pi / 2), (3.0, np.pi / 2)]:
        for animation in (0, "bend"):
            posed = chamfer.pose(asset, animation, time)
            assert posed.shape == rest.shape and posed.dtype == np.float32
            np.testing.assert_allclose(posed, bent(rest, angle), atol=2e-6)
    # A control: the bent pose is not the rest one.
    assert np.abs(chamfer.pose(asset, 0, 1.0) - rest).max() > 0.5


def test_pose_sets_morph_weights():
    cube = chamfer.bake(CUBE)
    rest = cube.topology_positions
    top = rest[:, 1] == 1.0
    risen = chamfer.pose(cube, weights=[1.0])
    np.testing.assert_allclose(risen[top, 1], 1.5)
    np.testing.assert_allclose(risen[~top], rest[~top])
    half = chamfer.pose(cube, "rise", 0.5)
    np.testing.assert_allclose(half[top, 1], 1.25)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda a, c: chamfer.pose(a, 3), "no such animation"),
        (lambda a, c: chamfer.pose(a, "run"), "no such animation"),
        (lambda a, c: chamfer.pose(a, [1]), "a number or a name"),
        (lambda a, c: chamfer.pose(c, weights=[1.0, 2.0]), "one per morph target"),
        (lambda a, c: chamfer.pose(c, weights=[float("nan")]), "finite"),
        (lambda a, c: chamfer.pose(a, 0, float("inf")), "time"),
    ],
)
def test_bad_poses_raise_options_errors(call, message):
    asset, cube = chamfer.bake(CYLINDER), chamfer.bake(CUBE)
    with pytest.raises(chamfer.OptionsError, match=message):
        call(asset, cube)


def test_a_still_asset_has_no_pose():
    still = chamfer.bake(SHAPES / "cube.obj")
    assert still.joints.shape == (0, 4) and still.rig["joints"] == 0
    with pytest.raises(chamfer.OptionsError, match="does not move"):
        chamfer.pose(still)


def test_more_joints_than_the_limit_is_a_limit_error():
    with pytest.raises(chamfer.LimitError, match="joints"):
        chamfer.bake(CYLINDER, max_joints=1)
