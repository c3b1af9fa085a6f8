"""Thesis commands subdivide, subdivideFace(s) and dual on the current object."""

from __future__ import annotations

import pytest

from livemod.dlfl import face_size_histogram, validate
from livemod.dlfl.commands import dual, subdivide, subdivideFace, subdivideFaces
from livemod.dlfl.errors import InvalidArgumentError, UnknownIdError
from livemod.dlfl.scene import Selection
from livemod.dlfl.subdivision import scheme_options
from tests.meshes import counts, snapshot


def test_star_import_gives_the_remeshing_commands():
    namespace: dict[str, object] = {}
    exec("from livemod.dlfl import *", namespace)
    for name in ("subdivide", "subdivideFace", "subdivideFaces", "dual"):
        assert callable(namespace[name])


def test_subdivide_by_thesis_name(scene):
    subdivide("catmull-clark")
    assert counts(scene) == (26, 48, 24)


# the appendix of Tett (2007): subdivide's schemes and their options, in its order
THESIS_SCHEMES = {
    "loop": (), "checker": ("thickness",), "simplest": (), "vertex-cut": ("offset",),
    "pentagon": ("offset",), "dual-pentagon": ("scale",), "honeycomb": (),
    "doo-sabin": ("check",), "doo-sabin-bc": ("check",), "doo-sabin-bc-new": ("length",),
    "corner-cut": (), "modified-corner-cut": ("thickness",), "root4": ("a", "twist"),
    "catmull-clark": (), "star": ("offset",), "sqrt3": (), "fractal": ("offset",),
    "stellate": (), "double-stellate": ("offset", "curve"), "dome": ("length", "scale"),
    "dual-12.6.4": ("scale",), "loop-style": ("length",), "linear-vertex": ("usequads",),
}


@pytest.mark.parametrize("scheme", list(THESIS_SCHEMES))
def test_every_thesis_scheme_reads_its_options_in_the_thesiss_order(scheme, monkeypatch):
    from livemod.dlfl import subdivision
    from livemod.dlfl.commands.subdivision import THESIS_KEYWORDS

    aliases = THESIS_KEYWORDS.get(scheme, {})
    thesis = [aliases.get(name, name) for name in THESIS_SCHEMES[scheme]]
    assert scheme_options(scheme)[:len(thesis)] == thesis
    calls: list[dict] = []
    monkeypatch.setattr(subdivision, "subdivide", lambda mesh, name, **o: calls.append(o))
    values = [0.25 + i for i in range(len(scheme_options(scheme)))]
    subdivide(scheme, *values)
    assert calls == [{**dict(zip(scheme_options(scheme), values, strict=True)),
                      "max_faces": None}]


def test_doo_sabin_bc_new_reads_its_one_thesis_option_as_the_length(scene):
    from livemod.dlfl.shapes import cube
    from livemod.dlfl.subdivision import subdivide as library_subdivide

    subdivide("doo-sabin-bc-new", 0.5)
    library = cube()
    library_subdivide(library, "doo-sabin-bc-new", length=0.5)
    assert snapshot(scene.mesh) == snapshot(library)


def test_positional_options_in_topmod_order(scene):
    assert scheme_options("double-stellate") == ["offset", "curve"]
    assert scheme_options("dome") == ["length", "scale"]
    subdivide("checker", 0.25)
    assert counts(scene) == (56, 108, 54)
    assert abs(scene.mesh.positions_view()).min() == 0.5


def test_positional_option_honoured_where_topmod_ignored_it(scene):
    subdivide("vertex-cut", 0.1)
    assert sorted(set(abs(scene.mesh.positions_view()).ravel().round(9))) == [0.8, 1.0]


def test_keyword_options(scene):
    subdivide("double-stellate", offset=0.5, curve=0.0)
    assert counts(scene) == (38, 72, 36)


def test_too_many_options_is_an_error(scene):
    before = snapshot(scene.mesh)
    with pytest.raises(InvalidArgumentError, match="at most 0 options"):
        subdivide("loop", 1)
    with pytest.raises(InvalidArgumentError, match=r"at most 1 options \(levels\)"):
        subdivide("catmull-clark", 1, 2)
    with pytest.raises(InvalidArgumentError, match="given twice"):
        subdivide("checker", 0.2, thickness=0.3)
    with pytest.raises(InvalidArgumentError, match="unknown subdivision scheme"):
        subdivide("catmull")
    assert snapshot(scene.mesh) == before


def test_composite_by_name(scene):
    subdivide("root3")
    assert counts(scene) == (14, 36, 24)


def test_subdivide_face_triangles_and_quads(scene):
    face = scene.mesh.face_ids()[0]
    subdivideFace(int(face), False)
    assert counts(scene) == (9, 16, 9)
    assert dict(face_size_histogram(scene.mesh)) == {3: 4, 4: 5}
    face = int(scene.mesh.face_ids()[0])
    n = scene.mesh.face_size(face)
    subdivideFace(face)
    assert counts(scene) == (9 + n + 1, 16 + 2 * n, 9 + n - 1)


def test_subdivide_faces_uses_the_selection(scene):
    ids = [int(f) for f in scene.mesh.face_ids()[:2]]
    scene.selection = Selection(faces=tuple(ids))
    subdivideFaces()
    m = scene.mesh
    validate(m)
    assert m.counts()[2] == 6 - 2 + 8


def test_subdivide_faces_refuses_bad_ids(scene):
    with pytest.raises(UnknownIdError, match="face id"):
        subdivideFaces([12345])
    with pytest.raises(InvalidArgumentError, match="faceids must be"):
        subdivideFaces("0")  # type: ignore[arg-type]
    with pytest.raises(InvalidArgumentError, match="faceid must be"):
        subdivideFace(1.5)  # type: ignore[arg-type]


def test_dual_both_methods(scene):
    dual()
    assert counts(scene) == (6, 12, 8)
    dual(True)
    assert counts(scene) == (8, 12, 6)


def test_modified_corner_cut_takes_topmods_second_variant(scene):
    subdivide("modified-corner-cut", 0.25, 2)
    assert counts(scene) == (24, 48, 26)
    assert sorted(set(abs(scene.mesh.positions_view()).ravel().round(12))) == [0.75, 1.0]
    with pytest.raises(InvalidArgumentError, match="variant must be 1"):
        subdivide("modified-corner-cut", 0.25, 0)
