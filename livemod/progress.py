"""The text progress bar of the command line (``livemod batch``, ``livemod render``)."""

from __future__ import annotations

import sys
from typing import TextIO


class ProgressBar:
    """Draws ``label [#####.....] k/N`` on a stream; call it with ``(done, total)``.

    On a terminal the bar is redrawn in place, and a call with a ``note`` (say,
    "variant 3 failed") leaves that line standing. On any other stream (a log
    file, a CI job) it writes a whole line at each tenth of the way, for every
    note and at the end, so that logs stay readable instead of holding one line
    of carriage returns.

    Args:
        label: the word in front of the bar.
        stream: where to draw (the current ``sys.stderr`` when None).
    """

    WIDTH = 30

    def __init__(self, label: str, stream: TextIO | None = None) -> None:
        self.label = label
        self.stream = stream if stream is not None else sys.stderr
        self.live = _is_terminal(self.stream)
        self._tenth = -1  # the last tenth of the way written, off a terminal

    def __call__(self, done: int, total: int, note: str = "") -> None:
        """Show that ``done`` of ``total`` items are finished, with an optional note."""
        line = self.line(done, total, note)
        finished = done >= total
        if self.live:
            self.stream.write("\r" + line + ("\n" if finished or note else ""))
        else:
            tenth = 10 * done // max(total, 1)
            if tenth == self._tenth and not (note or finished):
                return
            self._tenth = tenth
            self.stream.write(line + "\n")
        self.stream.flush()

    def line(self, done: int, total: int, note: str = "") -> str:
        """The text of the bar for ``done`` of ``total`` (no line ending)."""
        filled = self.WIDTH * min(max(done, 0), total) // max(total, 1)
        bar = "#" * filled + "." * (self.WIDTH - filled)
        return f"{self.label} [{bar}] {done}/{total}" + (f"  ({note})" if note else "")


def _is_terminal(stream: TextIO) -> bool:
    """Whether ``stream`` is a terminal (False for streams that cannot tell)."""
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):  # no isatty, or a closed stream
        return False
