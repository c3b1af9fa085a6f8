"""Tests of livemod.progress: the command line's progress bar."""

from __future__ import annotations

import io

from livemod.progress import ProgressBar


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_off_a_terminal_the_first_line_then_one_per_tenth():
    out = io.StringIO()
    bar = ProgressBar("batch", out)
    for done in range(1, 101):
        bar(done, 100)
    lines = out.getvalue().splitlines()
    assert "\r" not in out.getvalue()
    assert [line.split()[-1] for line in lines] == ["1/100"] + [f"{k}0/100" for k in range(1, 11)]
    assert lines[1] == "batch [###...........................] 10/100"
    assert lines[-1] == "batch [" + "#" * 30 + "] 100/100"


def test_off_a_terminal_every_note_is_written():
    out = io.StringIO()
    bar = ProgressBar("batch", out)
    bar(1, 32)
    bar(2, 32, "variant 1 failed")
    bar(3, 32)
    assert out.getvalue().splitlines() == [
        "batch [..............................] 1/32",
        "batch [#.............................] 2/32  (variant 1 failed)",
    ]


def test_on_a_terminal_redrawn_in_place_and_ended_with_a_newline():
    out = Terminal()
    bar = ProgressBar("rendering", out)
    for done in range(1, 4):
        bar(done, 3)
    assert out.getvalue() == (
        "\rrendering [##########....................] 1/3"
        "\rrendering [####################..........] 2/3"
        "\rrendering [##############################] 3/3\n"
    )


def test_on_a_terminal_a_note_stays_on_its_own_line():
    out = Terminal()
    bar = ProgressBar("batch", out)
    bar(1, 4, "variant 0 failed")
    bar(2, 4)
    assert out.getvalue().split("\n")[0].endswith("1/4  (variant 0 failed)")
    assert out.getvalue().endswith("2/4")


def test_a_stream_that_cannot_tell_counts_as_no_terminal():
    class Closed(io.StringIO):
        def isatty(self) -> bool:
            raise ValueError("I/O operation on closed file")

    assert not ProgressBar("x", Closed()).live
    assert ProgressBar("x", Terminal()).live
    assert ProgressBar("x", io.StringIO()).line(0, 0) == "x [" + "." * 30 + "] 0/0"
