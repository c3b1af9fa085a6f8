"""The ``param`` command: a script parameter with a default, a range and a doc line."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from ..errors import InvalidArgumentError
from ..params import make_spec
from ..run_context import current_run

__all__ = ["param"]


def param(
    name: str, default: Any, min: float | None = None, max: float | None = None,  # noqa: A002
    step: float | None = None, choices: Sequence[Any] | None = None, doc: str = "",
) -> Any:
    """Declare a script parameter and return its current value.

    The value is the one the runner was given (``livemod run --set name=value``,
    a ``livemod batch`` sweep, a slider in the window), checked against the
    declaration, or ``default`` when none was given. Numbers, bools, strings and
    choices from a list are supported.

    Raises:
        DLFLError: a bad declaration (name, range, default outside it), the same
            name declared twice with different settings, or a given value that
            does not fit the declaration.
    """
    spec = make_spec(name, default, min, max, step, choices, doc)
    run = current_run()
    earlier = run.declarations.get(name)
    if earlier is not None and earlier != spec:
        raise InvalidArgumentError(f"parameter {name!r} is declared twice with different settings")
    run.declarations[name] = spec
    if name in run.parameters:
        return spec.check(run.parameters[name])
    return default
