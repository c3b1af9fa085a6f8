"""Tests of livemod.dlfl.soup: the flat polygon soup, its next-corner links and the
names error messages give its faces and vertices."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from livemod.dlfl.soup import SoupNames, as_polygons, next_in_face

SQUARE = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]


@pytest.mark.parametrize("offsets", [[0, 4, 8, 12], [0, 3, 7, 8, 10], [0, 1, 2], [0, 2, 2, 5], [0]])
def test_next_in_face_wraps_every_face(offsets):
    # the all-k-gons shortcut and the general path must agree with a plain walk
    off = np.array(offsets, dtype=np.int64)
    expected = [start + (c - start + 1) % (end - start)
                for start, end in itertools.pairwise(offsets) for c in range(start, end)]
    assert next_in_face(off).tolist() == expected


def test_as_polygons_reads_lists_arrays_and_flat_indices_alike():
    lists = as_polygons(SQUARE, [[0, 1, 2], [0, 2, 3]])
    table = as_polygons(SQUARE, np.array([[0, 1, 2], [0, 2, 3]]))
    flat = as_polygons(SQUARE, [0, 1, 2, 0, 2, 3], offsets=[0, 3, 6])
    for soup in (lists, table, flat):
        assert soup.indices.tolist() == [0, 1, 2, 0, 2, 3]
        assert soup.offsets.tolist() == [0, 3, 6] and soup.sizes.tolist() == [3, 3]
        assert soup.next_corner.tolist() == [1, 2, 0, 4, 5, 3]
    ragged = as_polygons(SQUARE, [[0, 1, 2, 3], [3]])
    assert ragged.offsets.tolist() == [0, 4, 5]
    assert ragged.single_corners.tolist() == [False] * 4 + [True]
    assert as_polygons(SQUARE, np.zeros((0, 3), dtype=np.int64)).offsets.tolist() == [0]


def test_as_polygons_copies_the_positions():
    positions = np.array(SQUARE, dtype=np.float64)
    soup = as_polygons(positions, [[0, 1, 2, 3]])
    positions[0] = 9.0
    assert soup.positions[0].tolist() == [0.0, 0.0, 0.0]


def test_soup_names_use_file_lines_and_the_source_numbering():
    names = SoupNames("model.obj", np.array([12, 13, 15]), vertex_base=1)
    assert names.face(2) == "line 15" and names.vertex(0) == 1
    assert names.prefix([1]) == "model.obj:13: " and names.prefix() == "model.obj: "
    plain = SoupNames(None, None)
    assert plain.face(2) == "face 2" and plain.vertex(0) == 0
    assert plain.prefix([1]) == "polygons: "
