"""A glyph atlas from Pillow's default font and glyph-quad layout (numpy only).

Text is drawn as instanced quads. Each quad is one row of a ``(n, 13)`` float32
array: ``anchor (3)``, ``pixel offset (2)``, ``pixel size (2)``, ``atlas uv rect
(4: u0, v0, u1, v1)``, ``kind (1)`` and ``selected flag (1)``. The anchor is a world
point for labels, or a pixel position (from the top left) for the HUD. A solid
white cell of the atlas lets the same shader draw boxes behind text.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from PIL import Image, ImageDraw, ImageFont

FIRST_CHAR, LAST_CHAR = 32, 126
QUAD_FLOATS = 13
TAB_STOP = 96  # pixels between tab stops, for aligned columns (the font is proportional)

# palette slots of screen quads (rows of the renderer's PALETTE): text colours,
# then boxes (slots 1-3 and 9-11 are the id labels')
TEXT, ERROR_TEXT, LABEL_DIM, OK_TEXT, WARN_TEXT = 0, 4, 5, 6, 7
PANEL, ERROR_PANEL = 8, 12
TRACK, FILL, BUTTON = 13, 14, 15  # a slider's track or an unticked box, its fill or a
# ticked one, a button
MARGIN, PADDING = 8, 6  # pixels around the overlay's panels, and inside them


@dataclass(frozen=True)
class GlyphAtlas:
    """A one-channel glyph atlas.

    Attributes:
        image: ``(H, W)`` uint8 coverage; row 0 is the top.
        cell: ``(w, h)`` pixel size of every cell (glyph box).
        advance: ``(128,)`` float32 horizontal advance of each ASCII code.
        uv: ``(128, 4)`` float32 uv rect of each code's cell, v counted from the top.
        solid_uv: ``(4,)`` float32 uv rect inside the solid cell.
        line_height: pixels from one text line to the next.
    """

    image: np.ndarray
    cell: tuple[int, int]
    advance: np.ndarray
    uv: np.ndarray
    solid_uv: np.ndarray
    line_height: int


@lru_cache(maxsize=4)
def glyph_atlas(size: int = 13) -> GlyphAtlas:
    """Render printable ASCII with Pillow's default font into a 16-column atlas.

    Raises:
        RuntimeError: Pillow was built without FreeType (its bitmap font has no sizes).
    """
    font = ImageFont.load_default(size=size)
    if not isinstance(font, ImageFont.FreeTypeFont):
        raise RuntimeError("livemod's labels need Pillow built with FreeType")
    ascent, descent = font.getmetrics()
    cell_w, cell_h = int(font.getlength("W")) + 2, ascent + descent + 2
    codes = list(range(FIRST_CHAR, LAST_CHAR + 2))  # the last cell is the solid one
    rows = (len(codes) + 15) // 16
    image = Image.new("L", (16 * cell_w, rows * cell_h), 0)
    draw = ImageDraw.Draw(image)
    uv = np.zeros((128, 4), dtype=np.float32)
    advance = np.zeros(128, dtype=np.float32)
    width, height = image.size
    for slot, code in enumerate(codes):
        x, y = (slot % 16) * cell_w, (slot // 16) * cell_h
        if code <= LAST_CHAR:
            draw.text((x + 1, y + 1), chr(code), fill=255, font=font)
            uv[code] = (x / width, y / height, (x + cell_w) / width, (y + cell_h) / height)
            advance[code] = font.getlength(chr(code))
        else:
            draw.rectangle((x, y, x + cell_w - 1, y + cell_h - 1), fill=255)
            solid = np.array([(x + 2) / width, (y + 2) / height,
                              (x + cell_w - 2) / width, (y + cell_h - 2) / height],
                             dtype=np.float32)
    return GlyphAtlas(np.asarray(image), (cell_w, cell_h), advance, uv, solid,
                      ascent + descent + 3)


def layout_text(atlas: GlyphAtlas, lines: list[str], origin: tuple[float, float],
                kind: int = 0) -> np.ndarray:
    """Quads of screen text: ``lines`` from ``origin`` (pixels from the top left).

    Returns ``(n, QUAD_FLOATS)`` float32 with anchor ``(x, y, 0)`` and zero offset.
    """
    quads = []
    for row, line in enumerate(lines):
        y = origin[1] + row * atlas.line_height
        for x, code in _glyph_positions(atlas, line)[:-1]:
            quads.append([origin[0] + x, y, 0, 0, 0, *atlas.cell, *atlas.uv[code], kind, 0])
    return np.asarray(quads, dtype=np.float32).reshape(-1, QUAD_FLOATS)


def _glyph_positions(atlas: GlyphAtlas, line: str) -> list[tuple[float, int]]:
    """``(x offset, code)`` of each visible glyph of ``line``; a tab jumps to the next
    multiple of :data:`TAB_STOP`. The end of the line is ``(width, 32)``."""
    placed: list[tuple[float, int]] = []
    x = 0.0
    for char in line:
        if char == "\t":
            x = (x // TAB_STOP + 1) * TAB_STOP
            continue
        code = ord(char) if FIRST_CHAR <= ord(char) <= LAST_CHAR else ord("?")
        if char != " ":
            placed.append((x, code))
        x += float(atlas.advance[code])
    placed.append((x, ord(" ")))
    return placed


def box_quad(atlas: GlyphAtlas, x: float, y: float, w: float, h: float,
             kind: int) -> np.ndarray:
    """One ``(1, QUAD_FLOATS)`` solid screen rectangle (pixels from the top left)."""
    return np.array([[x, y, 0, 0, 0, w, h, *atlas.solid_uv, kind, 0]], dtype=np.float32)


def text_width(atlas: GlyphAtlas, line: str) -> float:
    """Pixel width of one line."""
    return _glyph_positions(atlas, line)[-1][0]


def wrap_line(atlas: GlyphAtlas, line: str, width: float, indent: str = "    ") -> list[str]:
    """``line`` broken into lines no wider than ``width`` pixels: at spaces, and
    inside a word only when the word alone is wider. Lines after the first start
    with ``indent`` (a continuation is told from a new line). A line that fits is
    returned as it is, spaces and all.

    Returns:
        At least one line; each fits ``width`` unless not even one character of
        it does (a window narrower than a glyph).
    """
    if text_width(atlas, line) <= width:
        return [line]
    words = line.split(" ")
    lines: list[str] = []
    current = _cut_to_fit(atlas, words[0], width, indent, lines)
    for word in words[1:]:
        candidate = f"{current} {word}"
        if text_width(atlas, candidate) <= width:
            current = candidate
        elif current.strip():
            lines.append(current)
            current = _cut_to_fit(atlas, indent + word, width, indent, lines)
        else:  # only the leading spaces so far: keep them with the word
            current = _cut_to_fit(atlas, candidate, width, indent, lines)
    lines.append(current)
    return lines


def _cut_to_fit(atlas: GlyphAtlas, text: str, width: float, indent: str,
                lines: list[str]) -> str:
    """Append to ``lines`` the pieces of ``text`` too wide for one line, cut
    anywhere; return the rest (which fits)."""
    while text_width(atlas, text) > width and len(text) > len(indent) + 1:
        cut = _fitting_prefix(atlas, text, width, len(indent) + 1)
        lines.append(text[:cut])
        text = indent + text[cut:]
    return text


def _fitting_prefix(atlas: GlyphAtlas, text: str, width: float, least: int) -> int:
    """The length of the longest prefix of ``text`` no wider than ``width`` (at
    least ``least`` characters, so that each cut makes progress)."""
    edges = np.cumsum([float(atlas.advance[ord(c) if FIRST_CHAR <= ord(c) <= LAST_CHAR
                                           else ord("?")]) for c in text])
    return max(int(np.searchsorted(edges, width, side="right")), least)


def layout_labels(atlas: GlyphAtlas, anchors: np.ndarray, ids: np.ndarray, kind: int,
                  selected: np.ndarray) -> np.ndarray:
    """Quads for numeric id labels centred on world ``anchors``, vectorized.

    Args:
        anchors: ``(n, 3)`` world positions.
        ids: ``(n,)`` non-negative integer ids.
        kind: colour key for the shader (1 face, 2 edge, 3 vertex).
        selected: ``(n,)`` bool, drawn highlighted.

    Returns:
        ``(n_boxes + n_digits, QUAD_FLOATS)`` float32: one box per label, then digits.
    """
    ids = np.asarray(ids, dtype=np.int64)
    n = len(ids)
    if n == 0:
        return np.zeros((0, QUAD_FLOATS), dtype=np.float32)
    ndigits = np.maximum(np.floor(np.log10(np.maximum(ids, 1))).astype(np.int64) + 1, 1)
    digit_w = float(atlas.advance[ord("0")])
    cell_w, cell_h = atlas.cell
    widths = ndigits * digit_w
    label_of = np.repeat(np.arange(n), ndigits)
    first = np.cumsum(ndigits) - ndigits
    pos = np.arange(len(label_of)) - first[label_of]
    power = ndigits[label_of] - 1 - pos
    digits = (ids[label_of] // 10 ** power) % 10
    glyphs = np.zeros((len(label_of), QUAD_FLOATS), dtype=np.float32)
    glyphs[:, 0:3] = anchors[label_of]
    glyphs[:, 3] = -widths[label_of] / 2 + pos * digit_w - 1
    glyphs[:, 4] = -cell_h / 2
    glyphs[:, 5:7] = (cell_w, cell_h)
    glyphs[:, 7:11] = atlas.uv[ord("0") + digits]
    glyphs[:, 11], glyphs[:, 12] = kind, selected[label_of]
    boxes = np.zeros((n, QUAD_FLOATS), dtype=np.float32)
    boxes[:, 0:3] = anchors
    boxes[:, 3], boxes[:, 4] = -widths / 2 - 3, -cell_h / 2 + 1
    boxes[:, 5], boxes[:, 6] = widths + 6, cell_h - 2
    boxes[:, 7:11] = atlas.solid_uv
    boxes[:, 11], boxes[:, 12] = kind + 8, selected
    return np.concatenate([boxes, glyphs])
