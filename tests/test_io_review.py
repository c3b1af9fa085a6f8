"""Regression tests for the bugs found in the I/O review."""

from __future__ import annotations

import os
import stat
import warnings

import numpy as np
import pytest

from livemod.dlfl import DLFLError, genus, validate
from livemod.dlfl.arrays import mesh_arrays
from livemod.dlfl.io import (
    load_mesh,
    read_dlfl,
    read_obj,
    read_stl,
    save_mesh,
    write_dlfl,
    write_obj,
)
from livemod.dlfl.io.dlflfile import dlfl_bytes, parse_dlfl
from livemod.dlfl.io.obj import parse_obj
from livemod.dlfl.io.stl import stl_bytes
from livemod.dlfl.shapes import torus

CUBE_V = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
CUBE_F = b"f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"
CUBE = CUBE_V + CUBE_F


def _cube():
    return read_obj(CUBE)


# ------------------------------------------------------------- OBJ line continuation


@pytest.mark.parametrize("fast", [True, False])
@pytest.mark.parametrize("newline", [b"\n", b"\r\n"])
def test_obj_backslash_continues_a_line(fast: bool, newline: bytes) -> None:
    data = (CUBE_V + b"f 1 4 \\\n    3 2\nv 0 0 \\\n 2\nf 1 2 -1\n").replace(b"\n", newline)
    soup = parse_obj(data, "c.obj", fast=fast)
    assert soup.offsets.tolist() == [0, 4, 7]
    assert soup.indices.tolist() == [0, 3, 2, 1, 0, 1, 8]
    assert soup.positions[8].tolist() == [0.0, 0.0, 2.0]
    assert soup.face_lines.tolist() == [9, 13]  # a joined line keeps its first line's number


def test_obj_continued_lines_keep_later_line_numbers() -> None:
    data = CUBE_V + b"f 1 2 \\\n 3\nf 1 2 x\n"
    with pytest.raises(DLFLError, match=r"^c\.obj:11: bad vertex index 'x'"):
        parse_obj(data, "c.obj")


# ------------------------------------------------------------- CR-only line endings


@pytest.mark.parametrize("fast", [True, False])
def test_obj_with_cr_line_endings_reads_every_line(fast: bool) -> None:
    soup = parse_obj(CUBE.replace(b"\n", b"\r"), "mac.obj", fast=fast)
    assert len(soup.positions) == 8 and len(soup.offsets) == 7


def test_dlfl_with_cr_line_endings_reads_every_line() -> None:
    text = dlfl_bytes(_cube()).replace(b"\n", b"\r")
    mesh = read_dlfl(text)
    assert (mesh.num_vertices, mesh.num_edges, mesh.num_faces) == (8, 12, 6)


def test_dlfl_without_a_header_end_is_refused() -> None:
    text = dlfl_bytes(_cube()).replace(b"#\n", b"")
    with pytest.raises(DLFLError, match=r"no '#' line"):
        parse_dlfl(text, "x.dlfl")


# ------------------------------------------------------------- .dlfl mtllib name


def test_dlfl_file_name_with_a_newline_still_reads_back(tmp_path) -> None:
    path = tmp_path / "a\n#\nv 0 0.dlfl"
    write_dlfl(_cube(), path)
    mesh = read_dlfl(path)
    assert (mesh.num_vertices, mesh.num_edges, mesh.num_faces) == (8, 12, 6)


# ------------------------------------------------------------- STL


def test_binary_stl_with_solid_header_and_trailing_bytes_is_not_empty() -> None:
    data = b"solid exported" + stl_bytes(torus())[14:] + b"\n"
    with pytest.raises(DLFLError, match=r"binary STL"):
        read_stl(data, name="t.stl")


ASCII_TRI = (b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
             b"vertex 0 1 0\nendloop\nendfacet\nendsolid t\n")


def test_ascii_stl_refuses_digit_underscores_like_obj() -> None:
    with pytest.raises(DLFLError, match=r"t\.stl:5: bad number '1_0'"):
        read_stl(ASCII_TRI.replace(b"vertex 1 0 0", b"vertex 1_0 0 0"), name="t.stl")


@pytest.mark.parametrize("name", [b"facet", b"vertex 1 2 3", b"outer loop", b"endloop"])
def test_ascii_stl_solid_name_may_hold_keywords(name: bytes) -> None:
    data = ASCII_TRI.replace(b"solid t\n", b"solid " + name + b"\n").replace(
        b"endsolid t", b"endsolid " + name)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mesh = read_stl(data, name="t.stl")
    validate(mesh)
    assert mesh.num_vertices == 3


# ------------------------------------------------------------- atomic writes


def test_new_file_mode_follows_the_umask(tmp_path) -> None:
    old = os.umask(0o077)
    try:
        write_obj(_cube(), tmp_path / "private.obj")
    finally:
        os.umask(old)
    assert stat.S_IMODE(os.stat(tmp_path / "private.obj").st_mode) == 0o600


@pytest.mark.parametrize("ext", ["obj", "dlfl", "ply"])
def test_round_trip_through_a_file_keeps_counts_genus_and_positions(ext: str, tmp_path) -> None:
    mesh = torus()
    save_mesh(mesh, tmp_path / f"t.{ext}")
    back = load_mesh(tmp_path / f"t.{ext}")
    assert (back.num_vertices, back.num_edges, back.num_faces) == (
        mesh.num_vertices, mesh.num_edges, mesh.num_faces)
    assert genus(back) == genus(mesh) == 1
    assert np.array_equal(mesh_arrays(back).positions, mesh_arrays(mesh).positions)


def test_replacing_a_read_only_file_keeps_its_mode(tmp_path) -> None:
    path = tmp_path / "ro.obj"
    path.write_bytes(b"old")
    path.chmod(0o444)
    write_obj(_cube(), path)
    assert stat.S_IMODE(path.stat().st_mode) == 0o444
    assert read_obj(path).num_faces == 6
    assert os.listdir(tmp_path) == ["ro.obj"]
