"""Measurements of the picked elements, as the HUD shows them, and of the whole
mesh shown, off the main thread (GL-free).

One picked face tells its sides, area and normal; one edge its length; one vertex
its position and valence; two vertices their distance; one corner its face, vertex
and angle; several of a kind their total area, total length or extent. Everything
is read from the result's :class:`~livemod.dlfl.arrays.MeshArrays`, so it measures
exactly what is drawn.
"""

from __future__ import annotations

import concurrent.futures
import logging
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from livemod.dlfl.arrays import MeshArrays
from livemod.dlfl.scene import Selection


@dataclass(frozen=True)
class WholeMesh:
    """What the HUD says of the whole mesh shown: its genus and the volume it
    encloses (None for an open mesh, see
    :func:`~livemod.dlfl.analysis.enclosed_volume`, or for a closed one that
    cannot be measured).

    ``nonfinite``: how many vertices of a closed mesh have a position that is not
    finite (NaN or inf), which leaves its volume unmeasured; 0 when it was
    measured, or the mesh is open (it has no volume to miss).
    """

    genus: int
    volume: float | None
    nonfinite: int = 0

    def text(self) -> str:
        """``genus 1  volume 8``; no volume for an open mesh, and ``volume n/a, 2
        vertices not finite`` for a closed one with positions that are not."""
        if self.nonfinite:
            return f"genus {self.genus}  volume n/a, {_vertices_not_finite(self.nonfinite)}"
        if self.volume is None:
            return f"genus {self.genus}"
        inside_out = " (inside out)" if self.volume < 0 else ""
        return f"genus {self.genus}  volume {self.volume:.4g}{inside_out}"


def measure_whole(arrays: MeshArrays) -> WholeMesh:
    """The :class:`WholeMesh` facts of ``arrays`` (0.13 to 0.17 s for a million corners).
    The genus counts ids only; the volume is left unmeasured (not NaN) when a
    position of a closed mesh is not finite."""
    from livemod.dlfl.analysis import enclosed_volume, genus

    if not len(arrays.positions):
        return WholeMesh(0, None)
    if not arrays.face_hole.any():
        bad = int(np.count_nonzero(~np.isfinite(arrays.positions).all(axis=1)))
        if bad:
            return WholeMesh(genus(arrays), None, bad)
    return WholeMesh(genus(arrays), enclosed_volume(arrays))


_LOG = logging.getLogger("livemod.measure")

# meshes up to this many corners are measured at once (0.13-0.17 s on the dev VM), larger in
# the background
MEASURE_AT_ONCE = 1_000_000


class WholeMeshMeasurer:
    """Measures the mesh shown: at once when it is small, else in a thread of its own,
    so that a large upload does not hold the window for the half second or more the
    genus and volume of a million faces take; the newest mesh wins.

    :meth:`measure` is called with each mesh shown; :meth:`facts` says what is known
    of the last one (None until measured). The background job gets the interpreter
    only between frames while the window draws a large mesh on software GL (the draw
    holds it), so there its facts can take several seconds to appear.
    """

    def __init__(self) -> None:
        self._pool: concurrent.futures.ThreadPoolExecutor | None = None  # made when needed
        self._job: concurrent.futures.Future[WholeMesh] | None = None
        # the last job found done, and its facts
        self._known: tuple[concurrent.futures.Future[WholeMesh], WholeMesh | None] | None = None

    def _submit(self, arrays: MeshArrays) -> concurrent.futures.Future[WholeMesh]:
        """Measure ``arrays`` in the background thread, starting it again after
        :meth:`close` (the window closes it with each script it stops watching)."""
        if self._pool is None:
            self._pool = concurrent.futures.ThreadPoolExecutor(
                1, thread_name_prefix="livemod-measure")
        return self._pool.submit(measure_whole, arrays)

    def measure(self, arrays: MeshArrays | None) -> None:
        """Measure ``arrays`` (None: nothing is shown); an older job's answer is dropped."""
        if self._job is not None:
            self._job.cancel()  # not started yet: never run
        if arrays is None:
            self._job = None
        elif len(arrays.corner_vertex) > MEASURE_AT_ONCE:
            self._job = self._submit(arrays)
            self._job.add_done_callback(_log_failure)
        else:
            self._job = concurrent.futures.Future()
            self._job.set_result(measure_whole(arrays))

    def facts(self) -> WholeMesh | None:
        """The facts of the last mesh given, once measured; None before (or when none
        is shown, or it could not be measured: that failure is logged to the
        logger named "livemod.measure")."""
        job = self._job
        if self._known is not None and self._known[0] is job:
            return self._known[1]  # (asked every frame: the future's locks are not free)
        if job is None or not job.done():
            return None
        facts = None if job.cancelled() or job.exception() is not None else job.result()
        self._known = (job, facts)
        return facts

    def wait(self, timeout: float | None = None) -> WholeMesh | None:
        """Block until the last mesh is measured (for tests and scripted use)."""
        if self._job is not None:
            concurrent.futures.wait([self._job], timeout)
        return self.facts()

    def close(self, wait: bool = False) -> None:
        """Stop the thread: a job running finishes in the background, or before
        this returns when ``wait``. A later :meth:`measure` starts another."""
        pool, self._pool = self._pool, None
        if pool is not None:
            pool.shutdown(wait=wait, cancel_futures=True)


def _log_failure(job: concurrent.futures.Future[WholeMesh]) -> None:
    if not job.cancelled() and job.exception() is not None:
        _LOG.error("measuring the mesh shown failed; the HUD leaves out its genus and volume",
                   exc_info=job.exception())


def measure_lines(selection: Selection, arrays: MeshArrays | None) -> list[str]:
    """The HUD's measurement lines for ``selection`` on ``arrays`` (ids that are not
    in ``arrays``, as after a re-run that renumbered them, are left out)."""
    if arrays is None:
        return []
    lines = []
    for measure, ids, table in ((_faces, selection.faces, arrays.face_ids),
                                (_edges, selection.edges, arrays.edge_ids),
                                (_vertices, selection.vertices, arrays.vertex_ids),
                                (_corners, selection.corners, arrays.corner_ids)):
        dense = _dense(table, ids)
        if dense:
            lines += measure(arrays, [int(ids_i) for ids_i in table[dense]], dense)
    return lines


def _dense(table: np.ndarray, ids: Sequence[int]) -> list[int]:
    """Dense indices of the ``ids`` that ``table`` (an id array) holds, in pick order
    (one pass over the table: it may hold millions of ids, and picks are few)."""
    if not ids:
        return []
    found = np.flatnonzero(np.isin(table, np.asarray(ids, dtype=np.int64)))
    at = {int(table[i]): int(i) for i in found}
    return [at[i] for i in ids if i in at]


def _vertices_not_finite(count: int) -> str:
    return f"{count} {'vertex' if count == 1 else 'vertices'} not finite"


def _not_finite(arrays: MeshArrays, vertices: Sequence[int] | np.ndarray) -> str:
    """'' when the positions of dense ``vertices`` are all finite; else which are
    not, as ``vertex 7 not finite`` (its id) or ``3 vertices not finite`` (each
    vertex counted once)."""
    at = np.unique(np.asarray(vertices, dtype=np.int64))
    bad = at[~np.isfinite(arrays.positions[at]).all(axis=1)]
    if len(bad) == 1:
        return f"vertex {int(arrays.vertex_ids[bad[0]])} not finite"
    return _vertices_not_finite(len(bad)) if len(bad) else ""


def _ring(arrays: MeshArrays, face: int) -> np.ndarray:
    """Dense vertex indices of dense ``face``'s corners."""
    return arrays.corner_vertex[arrays.face_offsets[face]:arrays.face_offsets[face + 1]]


def _num(value: float) -> str:
    return f"{value:.4g}"


def _point(p: np.ndarray) -> str:
    return "(" + ", ".join(_num(float(x)) for x in p) + ")"


def face_area_normal(arrays: MeshArrays, face: int) -> tuple[float, np.ndarray]:
    """Area and ``(3,)`` unit normal of dense face ``face`` (Newell's method, so
    non-planar faces get their best-fit normal); the normal is zero for a
    degenerate face."""
    ring = arrays.positions[_ring(arrays, face)].astype(np.float64)
    # relative to a corner: the cross products of far-off absolute positions cancel
    # to nothing (a unit square at 1e8 had area 0)
    ring -= ring[0]
    twice = np.cross(ring, np.roll(ring, -1, axis=0)).sum(axis=0)
    length = float(np.linalg.norm(twice))
    return length / 2.0, twice / length if length > 0 else np.zeros(3)


def _faces(arrays: MeshArrays, ids: list[int], dense: list[int]) -> list[str]:
    why = _not_finite(arrays, np.concatenate([_ring(arrays, f) for f in dense]))
    areas = [] if why else [face_area_normal(arrays, f) for f in dense]
    if len(dense) > 1:
        total = f"n/a, {why}" if why else _num(sum(a for a, _ in areas))
        return [f"{len(dense)} faces: area {total}"]
    sides = int(arrays.face_sizes[dense[0]])
    kind = " (hole)" if arrays.face_hole[dense[0]] else ""
    if why:
        return [f"face {ids[0]}{kind}: {sides} sides, area and normal n/a, {why}"]
    area, normal = areas[0]
    return [f"face {ids[0]}{kind}: {sides} sides, area {_num(area)}, normal {_point(normal)}"]


def _edge_ends(arrays: MeshArrays, edge: int) -> tuple[int, int]:
    """Dense vertex indices of an edge's two ends."""
    corner = arrays.edge_corners[edge, 0]
    return (int(arrays.corner_vertex[corner]),
            int(arrays.corner_vertex[arrays.edge_corners[edge, 1]]))


def _edges(arrays: MeshArrays, ids: list[int], dense: list[int]) -> list[str]:
    ends = [_edge_ends(arrays, e) for e in dense]
    why = _not_finite(arrays, np.ravel(ends))
    lengths = [] if why else [float(np.linalg.norm(arrays.positions[a] - arrays.positions[b]))
                              for a, b in ends]
    if len(dense) > 1:
        return [f"{len(dense)} edges: length {f'n/a, {why}' if why else _num(sum(lengths))}"]
    a, b = ends[0]
    between = f"vertices {int(arrays.vertex_ids[a])}-{int(arrays.vertex_ids[b])}"
    if why:
        return [f"edge {ids[0]}: {between}, length n/a, {why}"]
    return [f"edge {ids[0]}: length {_num(lengths[0])}, {between}"]


def _vertices(arrays: MeshArrays, ids: list[int], dense: list[int]) -> list[str]:
    points = arrays.positions[dense]
    why = _not_finite(arrays, dense)
    if len(dense) == 1:
        valence = int(np.count_nonzero((arrays.corner_vertex == dense[0])
                                       & (arrays.corner_edge >= 0)))
        if why:  # (the coordinates say which are not)
            return [f"vertex {ids[0]}: valence {valence}, position not finite "
                    f"{_point(points[0])}"]
        return [f"vertex {ids[0]} at {_point(points[0])}, valence {valence}"]
    if why:
        what = "distance and delta" if len(dense) == 2 else "extent"
        head = f"vertices {ids[0]}-{ids[1]}" if len(dense) == 2 else f"{len(dense)} vertices"
        return [f"{head}: {what} n/a, {why}"]
    if len(dense) == 2:
        delta = points[1] - points[0]
        return [f"vertices {ids[0]}-{ids[1]}: distance {_num(float(np.linalg.norm(delta)))}, "
                f"delta {_point(delta)}"]
    extent = points.max(axis=0) - points.min(axis=0)
    return [f"{len(dense)} vertices: extent {_point(extent)}"]


def corner_angle(arrays: MeshArrays, corner: int) -> float:
    """Degrees between the two edges at dense corner ``corner`` (0 when either is
    degenerate, as at a point-sphere)."""
    before, here, after = arrays.positions[_corner_vertices(arrays, corner)]
    u, w = before - here, after - here
    norms = float(np.linalg.norm(u) * np.linalg.norm(w))
    if norms == 0:
        return 0.0
    return math.degrees(math.acos(min(max(float(u @ w) / norms, -1.0), 1.0)))


def _corner_vertices(arrays: MeshArrays, corner: int) -> np.ndarray:
    """Dense indices of the vertices at dense ``corner`` and at its face's corners
    before and after it (what its angle is measured from)."""
    face = arrays.corner_face[corner]
    start, stop = arrays.face_offsets[face], arrays.face_offsets[face + 1]
    around = start + (corner - start + np.array([-1, 0, 1])) % (stop - start)
    return arrays.corner_vertex[around]


def _corners(arrays: MeshArrays, ids: list[int], dense: list[int]) -> list[str]:
    lines = []
    for cid, corner in list(zip(ids, dense, strict=True))[:2]:
        face = int(arrays.face_ids[arrays.corner_face[corner]])
        vertex = int(arrays.vertex_ids[arrays.corner_vertex[corner]])
        why = _not_finite(arrays, _corner_vertices(arrays, corner))
        angle = f"n/a, {why}" if why else f"{corner_angle(arrays, corner):.1f} deg"
        lines.append(f"corner {cid}: face {face} at vertex {vertex}, angle {angle}")
    if len(dense) > 2:
        lines.append(f"... {len(dense) - 2} more corners")
    return lines
