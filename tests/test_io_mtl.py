"""Tests of livemod.dlfl.io.mtl: face colours as materials and MTL libraries."""

from __future__ import annotations

import math

import numpy as np

from livemod.dlfl.colors import MODELLING_COLOR
from livemod.dlfl.io.mtl import (
    face_colors_of,
    materials_in_force,
    materials_of,
    mtl_bytes,
    parse_mtl,
    runs,
)

NAN = (math.nan, math.nan, math.nan)


def test_one_material_per_colour_and_default_for_faces_without_one():
    colors = np.array([(1, 0, 0), NAN, (1, 0, 0), (0, 0.2, 1)], dtype=np.float32)
    materials = materials_of(colors)
    named = [materials.names[i] for i in materials.index.tolist()]
    assert named == ["color_ff0000", "default", "color_ff0000", "color_0033ff"]
    kd = dict(zip(materials.names, materials.kd.tolist(), strict=True))
    assert kd["default"] == np.float32(MODELLING_COLOR).tolist()


def test_colours_of_one_8_bit_hex_get_distinct_names():
    colors = np.array([(1.0, 0, 0), (0.999, 0, 0)], dtype=np.float32)
    assert sorted(materials_of(colors).names) == ["color_ff0000", "color_ff0000_2"]


def test_a_library_reads_back_to_the_same_float32_colours():
    colors = np.array([(0.1, 0.2, 0.3), (1 / 3, 0.5, 0.7)], dtype=np.float32)
    materials = materials_of(colors)
    library = parse_mtl(mtl_bytes(materials))
    back = np.array([library[name] for name in materials.names], dtype=np.float32)
    np.testing.assert_array_equal(back, materials.kd)


def test_parse_mtl_keeps_kd_of_each_material_and_passes_over_the_rest():
    text = (b"# a comment\nnewmtl a\nKa 0 0 0\nKd 0.5 0.25 1  # blue\nillum 2\n"
            b"newmtl b\nKd spectral file.rfl\nnewmtl c\nKd 2 -1 nan\nnewmtl d\n"
            b"Kd 0.1 0.2 0.3\nnewmtl e f\nKd 1 1 1\nmap_Kd texture.png\n")
    assert parse_mtl(text) == {"a": (0.5, 0.25, 1.0), "d": (0.1, 0.2, 0.3),
                               "e f": (1.0, 1.0, 1.0)}
    assert parse_mtl(b"Kd 1 0 0\n") == {}  # no newmtl yet: nothing to name


def test_runs_cut_the_faces_where_the_material_changes():
    assert runs(np.array([0, 0, 1, 1, 1, 0, 2])) == [(0, 2), (2, 5), (5, 6), (6, 7)]
    assert runs(np.zeros(0, dtype=np.int64)) == []


def test_each_face_takes_the_material_last_named_before_it():
    materials = [(3, "a"), (7, "b")]
    assert materials_in_force(materials, np.array([2, 4, 6, 8])) == [None, "a", "a", "b"]
    assert materials_in_force([], np.array([1, 2])) == [None, None]


def test_faces_of_unknown_materials_have_no_colour():
    colors = face_colors_of(["a", None, "zz"], {"a": (1.0, 0.0, 0.0)})
    assert colors is not None and colors[0].tolist() == [1.0, 0.0, 0.0]
    assert np.isnan(colors[1:]).all()
    assert face_colors_of(["zz", None], {"a": (1.0, 0.0, 0.0)}) is None
