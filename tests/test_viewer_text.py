"""Screen text (GL-free): id label layout, and breaking long lines to fit a width."""

from __future__ import annotations

import numpy as np

from livemod.viewer.text import (
    QUAD_FLOATS,
    glyph_atlas,
    layout_labels,
    text_width,
    wrap_line,
)

NAMES = ", ".join(["catmull-clark", "doo-sabin", "doo-sabin-bc-new", "double-stella"] * 6)


def test_a_line_that_fits_is_kept_as_it_is() -> None:
    atlas = glyph_atlas()
    line = "  File 'model.py', line 3"
    assert wrap_line(atlas, line, text_width(atlas, line)) == [line]


def test_a_long_line_breaks_at_spaces_within_the_width() -> None:
    atlas = glyph_atlas()
    line = f"ValueError: unknown scheme 'catmul-clark'; the schemes are {NAMES}"
    lines = wrap_line(atlas, line, 300.0)
    assert len(lines) > 3
    assert all(text_width(atlas, piece) <= 300.0 for piece in lines)
    assert all(piece.startswith("    ") and not piece.startswith("     ")
               for piece in lines[1:])  # continuations are indented, once
    # nothing is lost: the words come back in order
    assert " ".join(piece.strip() for piece in lines) == line


def test_a_word_wider_than_the_window_is_cut() -> None:
    atlas = glyph_atlas()
    word = "x" * 200
    lines = wrap_line(atlas, f"a {word} b", 100.0, indent="  ")
    assert all(text_width(atlas, piece) <= 100.0 for piece in lines)
    assert "".join(piece.replace(" ", "") for piece in lines) == f"a{word}b"
    assert lines[0] == "a" and len(lines) > 3


def test_leading_spaces_stay_with_the_first_word() -> None:
    atlas = glyph_atlas()
    line = "    " + " ".join(["raise"] * 40)
    lines = wrap_line(atlas, line, 150.0)
    assert lines[0].startswith("    raise") and len(lines) > 1


def test_label_layout_has_one_box_and_one_glyph_per_digit() -> None:
    atlas = glyph_atlas()
    quads = layout_labels(atlas, np.zeros((3, 3)), np.array([0, 7, 1234]), 1,
                          np.array([False, True, False]))
    assert quads.shape == (3 + 1 + 1 + 4, QUAD_FLOATS)
    digits_of_1234 = quads[5:, 7]
    expected = atlas.uv[[ord(c) for c in "1234"], 0]
    np.testing.assert_allclose(digits_of_1234, expected)
    assert quads[1, 12] == 1.0 and quads[0, 12] == 0.0
