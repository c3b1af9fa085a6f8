"""Finding a script's param() declarations without running it, and checking values."""

from __future__ import annotations

from pathlib import Path

import pytest

from livemod.dlfl.errors import FileFormatError, InvalidArgumentError
from livemod.runner import ScriptFailedError
from livemod.runner.declarations import check_values, declared_parameters, describe

LITERAL = '''from livemod.dlfl import *
t = param("thickness", 0.1, min=0.01, max=0.5, doc="rod radius")
n = param("count", 3, min=1)
scheme = param("scheme", "loop", choices=["loop", "doo-sabin"])
raise SystemExit("a script with literal declarations is never run")
'''

COMPUTED = '''from livemod.dlfl import *
base = 2 * 0.05
t = param("thickness", base, min=0.0)
'''


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "model.py"
    path.write_text(text)
    return path


def test_literal_declarations_are_read_without_running(tmp_path: Path) -> None:
    specs = declared_parameters(write(tmp_path, LITERAL))
    assert list(specs) == ["thickness", "count", "scheme"]
    assert describe(specs.values()) == [
        "thickness = 0.1  [float] (range 0.01..0.5)  rod radius",
        "count = 3  [int] (range 1..inf)",
        "scheme = 'loop'  [choice] (choices 'loop', 'doo-sabin')",
    ]


def test_computed_declarations_are_found_by_running_once(tmp_path: Path) -> None:
    specs = declared_parameters(write(tmp_path, COMPUTED))
    assert specs["thickness"].default == pytest.approx(0.1)


def test_a_literal_declaration_the_run_does_not_reach_is_listed_too(tmp_path: Path) -> None:
    specs = declared_parameters(write(tmp_path, COMPUTED + (
        'if t > 1:\n    big = param("big", True)\n'
        'if t > 2:\n    huge = param("huge", 2 * t)\n')))  # computed and not run: unknown
    assert list(specs) == ["thickness", "big"]
    assert describe([specs["big"]]) == ["big = True  [bool]"]


def test_values_are_checked_against_the_declarations(tmp_path: Path) -> None:
    specs = declared_parameters(write(tmp_path, LITERAL))
    assert check_values(specs, {"count": "4", "thickness": 0.2}) == {"count": 4, "thickness": 0.2}
    with pytest.raises(InvalidArgumentError, match=r"declares no parameter 'cuont'; did you mean 'count'\? \(it declares: thickness, count, scheme\)"):
        check_values(specs, {"cuont": 4})
    with pytest.raises(InvalidArgumentError, match="above its maximum 0.5"):
        check_values(specs, {"thickness": 0.9})


def test_a_malformed_declaration_names_its_line(tmp_path: Path) -> None:
    path = write(tmp_path, 'from livemod.dlfl import *\n\nparam("x", 5, min=9)\n')
    with pytest.raises(InvalidArgumentError,
                       match=r"model.py:3: parameter 'x' = 5 is below its minimum 9"):
        declared_parameters(path)


def test_a_script_that_is_not_python_is_a_file_format_error(tmp_path: Path) -> None:
    path = write(tmp_path, 'from livemod.dlfl import *\nparam("x", 5)\nif True\n')
    with pytest.raises(FileFormatError, match=r"model.py:3: syntax error: ") as failed:
        declared_parameters(path)
    assert (failed.value.path, failed.value.line) == (str(path), 3)


def test_a_script_run_for_its_declarations_that_fails_names_its_line(tmp_path: Path) -> None:
    path = write(tmp_path, 'from livemod.dlfl import *\nn = param("n", 2 * 2)\n1 / 0\n')
    with pytest.raises(ScriptFailedError, match=r"^running .*model.py to find its "
                       r"parameters failed: .*model.py:3: ZeroDivisionError") as failed:
        declared_parameters(path)
    assert (failed.value.error.file, failed.value.error.line) == (str(path), 3)
