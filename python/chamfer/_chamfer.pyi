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
#: The section schema: the drawings' section keywords, chamfer draw's --section.
SECTION_SCHEMA: List[Dict[str, Any]]
ANIMATION_SCHEMA: List[Dict[str, Any]]
#: The line roles' styles: the drawings' style keywords, chamfer draw's style flags.
DRAWING_STYLE_SCHEMA: List[Dict[str, Any]]

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
    max_joints: Optional[int]
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

class SectionOptions(TypedDict, total=False):
    """A section plane (chamfer.SECTION_SCHEMA); a drawing takes one plane."""

    section: Optional[Sequence[float]]
    section_box: Optional[Sequence[float]]

class DrawingStyleOptions(TypedDict, total=False):
    """The line roles' styles and the hatch (chamfer.DRAWING_STYLE_SCHEMA)."""

    cut_weight: Optional[float]
    cut_color: Optional[Sequence[float]]
    cut_dash: Optional[Sequence[float]]
    hatch_weight: Optional[float]
    hatch_color: Optional[Sequence[float]]
    hatch_dash: Optional[Sequence[float]]
    silhouette_weight: Optional[float]
    silhouette_color: Optional[Sequence[float]]
    silhouette_dash: Optional[Sequence[float]]
    boundary_weight: Optional[float]
    boundary_color: Optional[Sequence[float]]
    boundary_dash: Optional[Sequence[float]]
    visible_weight: Optional[float]
    visible_color: Optional[Sequence[float]]
    visible_dash: Optional[Sequence[float]]
    intersection_weight: Optional[float]
    intersection_color: Optional[Sequence[float]]
    intersection_dash: Optional[Sequence[float]]
    hidden_weight: Optional[float]
    hidden_color: Optional[Sequence[float]]
    hidden_dash: Optional[Sequence[float]]
    hatch_spacing: Optional[float]
    hatch_angle: Optional[float]

class DrawOptions(ViewOptions, SectionOptions, DrawingStyleOptions, BakeOptions, total=False):
    """The drawings' keywords: the view's, the section's, the styles' and, for a mesh, the bake's."""

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
    @property
    def joints(self) -> npt.NDArray[np.uint16]: ...
    @property
    def weights(self) -> npt.NDArray[np.float32]: ...
    @property
    def morph_starts(self) -> npt.NDArray[np.uint32]: ...
    @property
    def morph_vertices(self) -> npt.NDArray[np.uint32]: ...
    @property
    def morph_deltas(self) -> npt.NDArray[np.float32]: ...
    @property
    def rig(self) -> Dict[str, object]: ...
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
def pose(
    asset: Asset,
    animation: Optional[Union[int, str]] = None,
    time: float = 0.0,
    weights: Optional[Sequence[float]] = None,
) -> npt.NDArray[np.float32]: ...
def decode(data: bytes, name: str = "<bytes>") -> Asset: ...
def draw_svg(
    source: Union[Asset, _Path],
    output: Optional[_Path] = None,
    *,
    width: int = 1024,
    height: int = 768,
    hidden: bool = False,
    classes: Optional[Sequence[str]] = None,
    scale: Optional[Union[float, str]] = None,
    units: str = "mm",
    title: Optional[str] = None,
    **options: Unpack[DrawOptions],
) -> str: ...
def draw_pdf(
    source: Union[Asset, _Path],
    output: Optional[_Path] = None,
    *,
    width: int = 1024,
    height: int = 768,
    hidden: bool = False,
    classes: Optional[Sequence[str]] = None,
    scale: Optional[Union[float, str]] = None,
    units: str = "mm",
    title: Optional[str] = None,
    **options: Unpack[DrawOptions],
) -> bytes: ...
def draw_dxf(
    source: Union[Asset, _Path],
    output: Optional[_Path] = None,
    *,
    width: int = 1024,
    height: int = 768,
    hidden: bool = False,
    classes: Optional[Sequence[str]] = None,
    scale: Optional[Union[float, str]] = None,
    units: str = "mm",
    title: Optional[str] = None,
    **options: Unpack[DrawOptions],
) -> str: ...
