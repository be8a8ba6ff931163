"""Type stubs of the extension module (python/src/*.rs); the docstrings live there."""

import os
import pathlib
import sys
from typing import Any, Dict, List, Optional, Sequence, Tuple, TypedDict, Union

import numpy as np
import numpy.typing as npt

if sys.version_info >= (3, 11):
    from typing import Unpack
else:
    from typing_extensions import Unpack

_Path = Union[str, "os.PathLike[str]"]

__version__: str
FORMAT_VERSION: int
EDGE_FLAGS: List[Tuple[str, int]]
#: (name, "float" | "int" | "bool", help) of every bake option.
OPTIONS: List[Tuple[str, str, str]]
BAKE_SCHEMA: List[Dict[str, Any]]
#: The view schema: draw_svg's camera keywords, chamfer draw's camera flags.
VIEW_SCHEMA: List[Dict[str, Any]]

class BakeOptions(TypedDict, total=False):
    """The bake options (the schema's "bake" group, chamfer.OPTIONS); None leaves one at its default."""

    weld_epsilon: Optional[float]
    weld_rel: Optional[float]
    coplanar_deg: Optional[float]
    crease_deg: Optional[float]
    radius: Optional[float]
    radius_rel: Optional[float]
    radius_valleys: Optional[bool]
    max_triangles: Optional[int]
    max_vertices: Optional[int]
    max_instances: Optional[int]
    max_input_bytes: Optional[int]
    intersections: Optional[bool]
    stitch_rel: Optional[float]
    stitch_epsilon: Optional[float]
    no_stitch: Optional[bool]

class EncodingOptions(TypedDict, total=False):
    """How Asset.encode and Asset.save store the asset (the schema's "encoding" group)."""

    compact: Optional[bool]
    position_bits: Optional[int]
    position_error: Optional[float]
    normal_bits: Optional[int]

class ViewOptions(TypedDict, total=False):
    """The orbit camera (chamfer.VIEW_SCHEMA); None leaves one at its default."""

    azimuth: Optional[float]
    elevation: Optional[float]
    distance: Optional[float]
    fov_y: Optional[float]
    ortho: Optional[bool]

class DrawOptions(ViewOptions, BakeOptions, total=False):
    """draw_svg's keywords: the view's and, for a mesh, the bake's."""

class ChamferError(Exception):
    path: Optional[str]

class ReadError(ChamferError): ...
class WriteError(ChamferError): ...
class FormatError(ChamferError): ...
class UnsupportedError(FormatError): ...
class MeshError(ChamferError): ...
class LimitError(ChamferError): ...
class OptionsError(ChamferError): ...
class ArrayError(ChamferError): ...
class AssetError(ChamferError): ...

class Asset:
    @property
    def stats(self) -> Dict[str, object]: ...
    @property
    def source(self) -> str: ...
    @property
    def generator(self) -> str: ...
    @property
    def settings(self) -> Dict[str, str]: ...
    @property
    def bounds(self) -> Tuple[Tuple[float, float, float], Tuple[float, float, float]]: ...
    @property
    def warnings(self) -> List[str]: ...
    @property
    def edge_count(self) -> int: ...
    @property
    def triangle_count(self) -> int: ...
    @property
    def render_positions(self) -> npt.NDArray[np.float32]: ...
    @property
    def render_normals(self) -> npt.NDArray[np.float32]: ...
    @property
    def mesh_indices(self) -> npt.NDArray[Union[np.uint16, np.uint32]]: ...
    @property
    def topology_positions(self) -> npt.NDArray[np.float32]: ...
    @property
    def edge_vertices(self) -> npt.NDArray[Union[np.uint16, np.uint32]]: ...
    @property
    def edge_attributes(self) -> npt.NDArray[np.uint32]: ...
    @property
    def edge_flags(self) -> npt.NDArray[np.uint16]: ...
    @property
    def edge_radii(self) -> npt.NDArray[np.float32]: ...
    @property
    def next_ends(self) -> npt.NDArray[Union[np.uint16, np.uint32]]: ...
    @property
    def cap_heads(self) -> npt.NDArray[Union[np.uint16, np.uint32]]: ...
    @property
    def intersection_segments(self) -> npt.NDArray[np.float32]: ...
    @property
    def intersection_starts(self) -> npt.NDArray[np.uint32]: ...
    def encode(self, **options: Unpack[EncodingOptions]) -> bytes: ...
    def save(self, path: _Path, **options: Unpack[EncodingOptions]) -> None: ...

def bake(
    source: Union[_Path, bytes], *, name: Optional[_Path] = None, **options: Unpack[BakeOptions]
) -> Asset: ...
def bake_arrays(
    vertices: npt.ArrayLike,
    faces: npt.ArrayLike,
    *,
    name: str = "arrays",
    **options: Unpack[BakeOptions],
) -> Asset: ...
def settings(**options: Unpack[BakeOptions]) -> List[Tuple[str, str]]: ...
def annotate(
    input: _Path,
    output: _Path,
    *,
    gltf_edges: Sequence[str] = ("extras",),
    **options: Unpack[BakeOptions],
) -> Dict[str, object]: ...
def bake_if_changed(input: _Path, output: _Path, **options: Unpack[BakeOptions]) -> bool: ...
def plan_folder(src: _Path, dst: _Path) -> List[Tuple[pathlib.Path, pathlib.Path]]: ...
def load(path: _Path) -> Asset: ...
def decode(data: bytes, name: str = "<bytes>") -> Asset: ...
def draw_svg(
    source: Union[Asset, _Path],
    output: Optional[_Path] = None,
    *,
    width: int = 1024,
    height: int = 768,
    hidden: bool = False,
    classes: Optional[Sequence[str]] = None,
    scale: Optional[float] = None,
    title: Optional[str] = None,
    **options: Unpack[DrawOptions],
) -> str: ...
