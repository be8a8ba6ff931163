"""Shared fixtures: the repository's meshes and the `chamfer` command the package is compared with.

The command is the release build of the workspace (target/release/chamfer, or $CHAMFER_CLI), which
`cargo test --workspace --release` builds before scripts/test.sh runs pytest; a missing one fails
the tests that need it (build it with `cargo build --release -p chamfer-preprocess --bin chamfer`).
"""

import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
FIXTURES = ROOT / "fixtures"
MESHES = FIXTURES / "meshes"
SHAPES = FIXTURES / "shapes"
BROKEN = FIXTURES / "broken"
HOSTILE = FIXTURES / "hostile"
MESH_SUFFIXES = (".obj", ".gltf", ".glb", ".ply", ".ply.gz")


def mesh_files(folder):
    return sorted(p for p in folder.iterdir() if p.name.lower().endswith(MESH_SUFFIXES))


def cli_path():
    if "CHAMFER_CLI" in os.environ:
        return Path(os.environ["CHAMFER_CLI"])
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    if not target.is_absolute():
        target = ROOT / target
    return target / "release" / "chamfer"


class Cli:
    """Runs the `chamfer` command."""

    def __init__(self, path):
        self.path = path

    def run(self, *args, check=True):
        result = subprocess.run(
            [str(self.path), *map(str, args)], capture_output=True, text=True, timeout=300
        )
        if check and result.returncode != 0:
            raise AssertionError(f"chamfer {' '.join(map(str, args))} failed:\n{result.stderr}")
        return result

    def bake(self, mesh, output, *flags):
        self.run("bake", mesh, "-o", output, *flags)
        return Path(output).read_bytes()

    def inspect(self, asset):
        return json.loads(self.run("inspect", asset, "--json").stdout)


@pytest.fixture(scope="session")
def cli():
    path = cli_path()
    if not path.is_file():
        pytest.fail(
            f"{path} is missing: build it with `cargo build --release -p chamfer-preprocess "
            "--bin chamfer` (or set CHAMFER_CLI)"
        )
    return Cli(path)
