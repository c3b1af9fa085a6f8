"""Face colours as materials: the ``usemtl`` runs that OBJ and TopMod's ``.dlfl``
write, and the Wavefront MTL library beside them (``newmtl`` and ``Kd``, one
material per colour).

Writing names a material after its colour's 8-bit hex (``color_ff9900``; another
float colour of the same hex gets ``color_ff9900_2``); faces without colour use
``default`` in the modelling colour, so a file colours every face. Reading takes
``newmtl`` and ``Kd r g b`` from each library (values clipped to ``[0, 1]``) and
passes over every other line; nothing a library holds is executed, and a
library that is missing or unreadable leaves its faces without colour, with a
:class:`~livemod.dlfl.errors.DLFLRepairWarning` and a note on the mesh.
"""

from __future__ import annotations

import math
import os
import warnings
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from ..colors import MODELLING_COLOR
from ..errors import DLFLRepairWarning
from .source import show_path

DEFAULT_MATERIAL = "default"
HOLE_MATERIAL = "hole"  # livemod's .dlfl files mark hole faces with it


@dataclass(frozen=True)
class Materials:
    """The materials of a mesh's faces.

    Attributes:
        names: ``(M,)`` material names.
        kd: ``(M, 3)`` float32 diffuse colour of each material.
        index: ``(F,)`` int64 material of each face.
    """

    names: list[str]
    kd: np.ndarray
    index: np.ndarray


def materials_of(face_colors: np.ndarray) -> Materials:
    """One material per distinct colour of the ``(F, 3)`` float32 ``face_colors``
    (NaN rows, faces without colour: :data:`DEFAULT_MATERIAL`)."""
    missing = np.isnan(face_colors[:, 0])
    keyed = np.where(missing[:, None], np.float32(-1), face_colors)
    kd, index = np.unique(keyed, axis=0, return_inverse=True)
    names: list[str] = []
    for row in kd.tolist():
        base = (DEFAULT_MATERIAL if row[0] < 0
                else "color_" + "".join(f"{round(v * 255):02x}" for v in row))
        name, copy = base, 1
        while name in names:
            copy += 1
            name = f"{base}_{copy}"
        names.append(name)
    kd[kd[:, 0] < 0] = MODELLING_COLOR
    return Materials(names, kd.astype(np.float32), index.reshape(-1).astype(np.int64))


def mtl_bytes(materials: Materials) -> bytes:
    """The MTL library of ``materials`` (each ``Kd`` reads back to the same float32)."""
    lines = ["# livemod MTL: one material per face colour"]
    for name, (red, green, blue) in zip(materials.names, materials.kd.tolist(), strict=True):
        lines += [f"newmtl {name}", f"Kd {red!r} {green!r} {blue!r}"]
    return ("\n".join(lines) + "\n").encode()


def runs(index: np.ndarray) -> list[tuple[int, int]]:
    """``(first, end)`` face ranges of one material each, from the ``(F,)`` ``index``."""
    cuts = np.flatnonzero(np.diff(index)) + 1
    bounds = [0, *cuts.tolist(), len(index)]
    return [(lo, hi) for lo, hi in zip(bounds[:-1], bounds[1:], strict=True) if hi > lo]


# ---------------------------------------------------------------------- reading


def parse_mtl(data: bytes) -> dict[str, tuple[float, float, float]]:
    """The ``Kd`` colour of every material of an MTL library (``newmtl`` names);
    a material without a readable ``Kd r g b`` is left out."""
    colors: dict[str, tuple[float, float, float]] = {}
    current: str | None = None
    for raw in data.splitlines():
        words = raw.split(b"#", 1)[0].split()
        if len(words) >= 2 and words[0] == b"newmtl":
            current = b" ".join(words[1:]).decode("utf-8", "replace")
        elif len(words) == 4 and words[0] == b"Kd" and current is not None:
            kd = _kd(words[1:])
            if kd is not None:
                colors[current] = kd
    return colors


def _kd(words: list[bytes]) -> tuple[float, float, float] | None:
    try:
        values = [float(w) for w in words]
    except ValueError:
        return None
    if not all(math.isfinite(v) for v in values):
        return None
    red, green, blue = (min(max(v, 0.0), 1.0) for v in values)
    return red, green, blue


def read_libraries(names: Iterable[str], folder: str, label: str, used: Iterable[str | None],
                   mesh_notes: list[str]) -> dict[str, tuple[float, float, float]]:
    """The materials of the MTL libraries ``names`` (as ``mtllib`` gives them,
    relative to ``folder``, the folder of the file that names them).

    A library that cannot be read leaves its faces without colour; it is noted in
    ``mesh_notes`` and warned about (:class:`DLFLRepairWarning`) when the faces
    use a material (``used``) other than ``default`` and ``hole``, the names
    TopMod's and livemod's files give faces without colour.
    """
    quiet = set(used) <= {None, DEFAULT_MATERIAL, HOLE_MATERIAL}
    colors: dict[str, tuple[float, float, float]] = {}
    for name in dict.fromkeys(names):
        path = os.path.join(folder, name)
        try:
            with open(path, "rb") as handle:
                colors.update(parse_mtl(handle.read()))
        except OSError as error:
            if quiet:
                continue
            why = "not found" if isinstance(error, FileNotFoundError) else error.strerror
            message = (f"{show_path(label)}: material library {name!r} {why}; its faces "
                       "have no colour")
            mesh_notes.append(message)
            warnings.warn(message, DLFLRepairWarning, stacklevel=4)
    return colors


def materials_in_force(materials: list[tuple[int, str]],
                       face_lines: np.ndarray) -> list[str | None]:
    """The ``usemtl`` material in force on each face: ``materials`` are ``(line,
    name)`` of the ``usemtl`` lines in file order, ``face_lines`` ``(F,)`` the
    faces' lines (None before the first ``usemtl``)."""
    if not materials:
        return [None] * len(face_lines)
    lines = np.array([line for line, _ in materials], dtype=np.int64)
    names: list[str | None] = [None, *(name for _, name in materials)]
    return [names[k] for k in np.searchsorted(lines, face_lines).tolist()]


def face_colors_of(in_force: list[str | None],
                   colors: dict[str, tuple[float, float, float]]) -> np.ndarray | None:
    """``(F, 3)`` float32 colours of faces whose materials are ``in_force`` (None:
    none), NaN rows where the material has no known colour; None when no face
    has one."""
    rows = [colors.get(name) if name is not None else None for name in in_force]
    if all(row is None for row in rows):
        return None
    nan = (math.nan, math.nan, math.nan)
    return np.array([nan if row is None else row for row in rows], dtype=np.float32)
