"""3MF: a writer of the printable mesh, one 3MF object per scene object.

A 3MF file is a zip package: ``[Content_Types].xml``, ``_rels/.rels`` and the
model ``3D/3dmodel.model``, an XML document of each object's vertices and
triangles (the drawn faces as fans from their head corners) in a unit,
``millimeter`` by default. Face colours become one ``m:colorgroup`` per object
(the distinct colours) and each triangle's ``pid``/``p1``. The XML is formatted
with whole-array numpy steps and deflated at a fast level.
"""

from __future__ import annotations

import os
import zipfile
from collections.abc import Iterator
from xml.sax.saxutils import quoteattr

import numpy as np

from ..errors import InvalidArgumentError
from ._numtext import format_floats, format_uints, join_columns
from ._scene_out import Objects, Part, parts
from .atomic import atomic_write

UNITS = ("micron", "millimeter", "centimeter", "inch", "foot", "meter")
_CORE = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
_MATERIAL = "http://schemas.microsoft.com/3dmanufacturing/material/2015/02"
_CONTENT_TYPES = (
    '<?xml version="1.0" encoding="UTF-8"?>\n<Types xmlns="http://schemas.openxmlformats.org/'
    'package/2006/content-types"><Default Extension="rels" ContentType="application/'
    'vnd.openxmlformats-package.relationships+xml"/><Default Extension="model" '
    'ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>\n')
_RELS = (
    '<?xml version="1.0" encoding="UTF-8"?>\n<Relationships xmlns="http://schemas.openxmlformats'
    '.org/package/2006/relationships"><Relationship Target="/3D/3dmodel.model" Id="rel0" '
    'Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>\n')
# rows per formatting step: the temporaries of a step stay small
_ROWS_PER_PASS = 1 << 16


def write_3mf(objects: Objects, path: str | os.PathLike[str], *, unit: str = "millimeter",
              face_colors: object = None) -> None:
    """Write objects as a 3MF package, atomically.

    Args:
        objects: a mesh, or ``(name, mesh)`` pairs (one 3MF object each, all
            placed on the build plate as they are).
        path: the target ``.3mf``.
        unit: what one coordinate unit is: ``micron``, ``millimeter`` (the
            default: a slicer reads 1.0 as 1 mm), ``centimeter``, ``inch``,
            ``foot`` or ``meter``.
        face_colors: see :func:`._scene_out.parts` (a colour group per object).

    Raises:
        InvalidArgumentError: an unknown unit, no object, or bad colours.
        OSError: the file cannot be written; an existing file is left intact.
    """
    if unit not in UNITS:
        raise InvalidArgumentError(f"unknown 3MF unit {unit!r}; use one of {', '.join(UNITS)}")
    pieces = model_pieces(parts(objects, face_colors), unit)
    with atomic_write(path) as handle, zipfile.ZipFile(
            handle, "w", zipfile.ZIP_DEFLATED, compresslevel=1) as package:
        package.writestr("[Content_Types].xml", _CONTENT_TYPES)
        package.writestr("_rels/.rels", _RELS)
        with package.open("3D/3dmodel.model", "w", force_zip64=True) as model:
            for piece in pieces:
                model.write(piece)


def model_pieces(objects: list[Part], unit: str) -> Iterator[bytes]:
    """The ``3D/3dmodel.model`` XML of ``objects``, in pieces."""
    yield (f'<?xml version="1.0" encoding="UTF-8"?>\n<model unit="{unit}" xml:lang="en-US" '
           f'xmlns="{_CORE}" xmlns:m="{_MATERIAL}">\n<resources>\n').encode()
    next_id = 1
    for part in objects:
        color_group = None
        if part.rgba is not None:
            color_group, next_id = next_id, next_id + 1
            yield from _color_group(part, color_group)
        yield (f'<object id="{next_id}" type="model" name={quoteattr(part.name)}>'
               "<mesh>\n<vertices>\n").encode()
        vertex_of, triangles = _compact(part)
        yield from _vertices(part.arrays.positions[vertex_of])
        yield b"</vertices>\n<triangles>\n"
        yield from _triangles(triangles, part, color_group)
        yield b"</triangles>\n</mesh></object>\n"
        next_id += 1
    items = "".join(f'<item objectid="{k}"/>' for k in _object_ids(objects))
    yield f"</resources>\n<build>{items}</build>\n</model>\n".encode()


def _object_ids(objects: list[Part]) -> list[int]:
    """The ids :func:`model_pieces` gives the objects (a colour group takes one first)."""
    ids, next_id = [], 1
    for part in objects:
        next_id += part.rgba is not None
        ids.append(next_id)
        next_id += 1
    return ids


def _compact(part: Part) -> tuple[np.ndarray, np.ndarray]:
    """``(vertex_of, triangles)``: the dense vertices the triangles use, and the
    ``(T, 3)`` triangles as indices into them (a vertex no triangle uses, such as
    a point-sphere, is left out: a printable mesh has none)."""
    a = part.arrays
    vertices = a.corner_vertex[part.corners][part.triangles]
    used = np.zeros(len(a.positions), dtype=bool)
    used[vertices] = True
    return np.flatnonzero(used), (np.cumsum(used) - 1)[vertices]


def _vertices(positions: np.ndarray) -> Iterator[bytes]:
    for start in range(0, len(positions), _ROWS_PER_PASS):
        rows = positions[start : start + _ROWS_PER_PASS]
        fields = format_floats(rows.ravel()).reshape(len(rows), 3, -1)
        yield join_columns(len(rows), [b'<vertex x="', fields[:, 0], b'" y="', fields[:, 1],
                                       b'" z="', fields[:, 2], b'"/>\n'])


def _triangles(triangles: np.ndarray, part: Part, color_group: int | None) -> Iterator[bytes]:
    colour_of = _colour_indices(part) if color_group is not None else None
    for start in range(0, len(triangles), _ROWS_PER_PASS):
        rows = triangles[start : start + _ROWS_PER_PASS]
        digits = format_uints(rows.ravel()).reshape(len(rows), 3, -1)
        tail: list[bytes | np.ndarray] = [b'"/>\n']
        if colour_of is not None:
            colours = format_uints(colour_of[part.faces[start : start + _ROWS_PER_PASS]])
            tail = [b'" pid="%d" p1="' % (color_group or 0), colours, b'"/>\n']
        yield join_columns(len(rows), [b'<triangle v1="', digits[:, 0], b'" v2="', digits[:, 1],
                                       b'" v3="', digits[:, 2], *tail])


def _colour_indices(part: Part) -> np.ndarray:
    """``(F,)`` int64: each face's index in its object's colour group."""
    assert part.rgba is not None
    _, inverse = np.unique(part.rgba.view("<u4").ravel(), return_inverse=True)
    return inverse.ravel()


def _color_group(part: Part, group: int) -> Iterator[bytes]:
    """The ``m:colorgroup`` of the distinct face colours, in sorted order."""
    assert part.rgba is not None
    distinct = np.unique(part.rgba.view("<u4").ravel()).view(np.uint8).reshape(-1, 4)
    colours = "".join(f'<m:color color="#{r:02X}{g:02X}{b:02X}{alpha:02X}"/>'
                      for r, g, b, alpha in distinct.tolist())
    yield f'<m:colorgroup id="{group}">{colours}</m:colorgroup>\n'.encode()
