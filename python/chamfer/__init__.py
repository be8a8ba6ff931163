"""Chamfer from Python: bake the feature edges of meshes into compact ``.chamfer`` assets.

    import chamfer
    asset = chamfer.bake("part.obj", crease_deg=40, radius_rel=0.005)
    asset.stats["edges"]["crease"]          # the keys of `chamfer inspect --json`
    asset.edge_vertices                     # numpy view of the section, no copy
    asset.save("part.chamfer")              # atomic: temporary file, then rename
    svg = chamfer.draw_svg(asset, azimuth=30, hidden=True)

Meshes in memory: ``bake_arrays(vertices, faces)`` or ``from_trimesh(mesh)``. Batch bakes of whole
folders on a Dask cluster: ``chamfer.dask.bake_folder`` (and ``python -m chamfer.dask``).

Every function releases the interpreter while it works, and every error is a ``ChamferError``
(ReadError, WriteError, FormatError, UnsupportedError, MeshError, LimitError, OptionsError,
ArrayError, AssetError) whose message names the file and the problem; ``error.path`` is the file.
The bake options are listed in ``help(chamfer.bake)`` and in ``chamfer.OPTIONS``; ``chamfer.BAKE_SCHEMA``
is their schema (the table ``chamfer bake``'s flags, the page and Bevy's ``.meta`` are made from), and
``chamfer.VIEW_SCHEMA`` the camera's (``draw_svg``'s keywords, ``chamfer draw``'s camera flags),
``chamfer.SECTION_SCHEMA`` and ``chamfer.DRAWING_STYLE_SCHEMA`` the section drawings' (``draw_svg``,
``draw_pdf`` and ``draw_dxf``; ``chamfer draw --section`` and its style flags).
"""

import enum as _enum
import functools as _functools
import textwrap as _textwrap

from . import _chamfer
from ._chamfer import (
    ANIMATION_SCHEMA,
    BAKE_SCHEMA,
    FORMAT_VERSION,
    VIEW_SCHEMA,
    SECTION_SCHEMA,
    DRAWING_STYLE_SCHEMA,
    OPTIONS,
    ArrayError,
    Asset,
    AssetError,
    ChamferError,
    FormatError,
    LimitError,
    MeshError,
    OptionsError,
    ReadError,
    UnsupportedError,
    WriteError,
    __version__,
    annotate,
    bake_arrays,
    bake_if_changed,
    decode,
    load,
    plan_folder,
    pose,
    settings,
)

_TYPES = {"number": "float", "count": "int", "flag": "bool", "numbers": "sequence of floats"}


def _keywords(schema, group):
    """The docstring's list of a schema group's keywords: name, type, help and default."""
    lines = []
    for entry in schema:
        if entry["group"] != group:
            continue
        default = "" if entry["default"] is None or entry["kind"] == "flag" else f" [default: {entry['default']}]"
        lines.append(f"  {entry['name']}: {_TYPES[entry['kind']]}")
        lines += _textwrap.wrap(entry["help"] + default, 92, initial_indent=" " * 6, subsequent_indent=" " * 6,
                                break_on_hyphens=False, break_long_words=False)
    return "\n".join(lines)


def _with_keywords(function, *tables):
    """``function`` (a compiled one, whose docstring cannot change) with the keyword lists its
    docstring's ``{name}`` fields ask for made from the schemas: one source for the flags, the
    keywords and their help."""

    @_functools.wraps(function)
    def documented(*args, **kwargs):
        return function(*args, **kwargs)

    documented.__doc__ = function.__doc__.format(**dict(tables))
    documented.__text_signature__ = function.__text_signature__
    return documented


_BAKE_KEYWORDS = ("bake_keywords", _keywords(BAKE_SCHEMA, "bake"))
bake = _with_keywords(_chamfer.bake, _BAKE_KEYWORDS)
_DRAW_KEYWORDS = (
    ("view_keywords", _keywords(VIEW_SCHEMA, "view")),
    ("section_keywords", _keywords(SECTION_SCHEMA, "section")),
    ("style_keywords", _keywords(DRAWING_STYLE_SCHEMA, "drawing_style")),
    _BAKE_KEYWORDS,
)
draw_svg = _with_keywords(_chamfer.draw_svg, *_DRAW_KEYWORDS)
draw_pdf = _chamfer.draw_pdf
draw_dxf = _chamfer.draw_dxf

EdgeFlags = _enum.IntFlag("EdgeFlags", dict(_chamfer.EDGE_FLAGS))
EdgeFlags.__doc__ = """The classes of an edge, bits of ``Asset.edge_flags`` (several can be set).

An edge with none of the bits is smooth: kept because it can become a contour. CREASE is
RIDGE | VALLEY.
"""
EdgeFlags.__module__ = __name__


def from_trimesh(mesh, *, name=None, **options):
    """Bakes a trimesh mesh (``trimesh.Trimesh``, or a ``trimesh.Scene``, flattened) into an Asset.

    The same as ``bake_arrays(mesh.vertices, mesh.faces, name=name, **options)``; ``name``
    defaults to the file trimesh loaded the mesh from. trimesh itself is not needed to import
    chamfer: anything with ``vertices`` (N, 3) and ``faces`` (M, 3) arrays works.
    """
    if not hasattr(mesh, "faces") and hasattr(mesh, "geometry"):
        # A Scene: its meshes with their transforms applied, as one mesh.
        mesh = mesh.to_mesh() if hasattr(mesh, "to_mesh") else mesh.dump(concatenate=True)
    if name is None:
        metadata = getattr(mesh, "metadata", None) or {}
        name = metadata.get("file_name") or metadata.get("name") or "trimesh"
    try:
        vertices, faces = mesh.vertices, mesh.faces
    except AttributeError as missing:
        error = ArrayError(f"{name}: from_trimesh() needs a mesh with vertices and faces ({missing})")
        error.path = name
        raise error from None
    return bake_arrays(vertices, faces, name=name, **options)


__all__ = [
    "FORMAT_VERSION",
    "OPTIONS",
    "BAKE_SCHEMA",
    "VIEW_SCHEMA",
    "SECTION_SCHEMA",
    "DRAWING_STYLE_SCHEMA",
    "ArrayError",
    "Asset",
    "AssetError",
    "ChamferError",
    "EdgeFlags",
    "FormatError",
    "LimitError",
    "MeshError",
    "OptionsError",
    "ReadError",
    "UnsupportedError",
    "WriteError",
    "__version__",
    "annotate",
    "bake",
    "bake_arrays",
    "bake_if_changed",
    "decode",
    "draw_dxf",
    "draw_pdf",
    "draw_svg",
    "from_trimesh",
    "load",
    "plan_folder",
    "settings",
]
