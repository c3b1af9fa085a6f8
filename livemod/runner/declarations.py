"""Find the parameters a script declares with ``param()``, and check values against them.

Most declarations are literal (``param("t", 0.1, min=0.0, max=1.0)``), so they are
read from the script's syntax tree without running it. A script whose ``param()``
calls compute their arguments is run once, headless, with the defaults.
"""

from __future__ import annotations

import ast
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from livemod.dlfl.errors import DLFLError, FileFormatError, InvalidArgumentError, did_you_mean
from livemod.dlfl.params import ParamSpec, make_spec

from .errors import ScriptFailedError
from .instrument import read_script

_PARAM_ARGS = ("name", "default", "min", "max", "step", "choices", "doc")


def declared_parameters(script: str | Path) -> dict[str, ParamSpec]:
    """The parameters ``script`` declares, by name, in the order of the script.

    When a ``param()`` call computes an argument, the script is run and what the
    run declared comes first, then the literal calls the run did not reach (a
    branch it did not take), in the order of the script.

    Raises:
        FileFormatError: the script is not Python (a syntax error, bytes not in
            its encoding).
        InvalidArgumentError: a declaration is malformed.
        ScriptFailedError: the script fails when it has to be run to find its
            declarations.
        OSError: the script cannot be read.
    """
    path = Path(script)
    source = script_source(path)
    specs = literal_declarations(source, path)
    if specs is not None:
        return specs
    ran = _run_for_declarations(path)
    readable = _readable_declarations(source, path)
    return {**ran, **{name: spec for name, spec in readable.items() if name not in ran}}


def script_source(path: Path | str) -> str:
    """The script's text (see :func:`~livemod.runner.instrument.read_script`).

    Raises:
        FileFormatError: its bytes are not text in its encoding.
        OSError: it cannot be read.
    """
    try:
        return read_script(str(path))
    except SyntaxError as exc:
        raise FileFormatError(f"{path}:{exc.lineno}: {exc.msg}", path=str(path),
                              line=exc.lineno) from None


def literal_declarations(source: str, path: str | Path) -> dict[str, ParamSpec] | None:
    """The declarations of ``source`` read from its syntax tree, without running it.

    Returns None when a ``param()`` call computes an argument (the script must
    be run to know its declarations).

    Raises:
        FileFormatError: a syntax error.
        InvalidArgumentError: a malformed literal declaration.
    """
    calls, literal = _param_calls(source, path)
    if all(args is not None for args in literal):
        return _specs(Path(path), calls, literal)
    return None


def _readable_declarations(source: str, path: str | Path) -> dict[str, ParamSpec]:
    """The declarations of the ``param()`` calls whose arguments are all literals."""
    calls, literal = _param_calls(source, path)
    kept = [(call, args) for call, args in zip(calls, literal, strict=True) if args is not None]
    return _specs(Path(path), [call for call, _ in kept], [args for _, args in kept])


def _param_calls(source: str, path: str | Path) -> tuple[list[ast.Call], list[Any]]:
    """The ``param()`` calls of ``source`` in source order, and each one's literal
    arguments (None for a call that computes one).

    Raises:
        FileFormatError: a syntax error.
    """
    try:
        tree = ast.parse(source, filename=str(path))
    except SyntaxError as exc:
        raise FileFormatError(f"{path}:{exc.lineno}: syntax error: {exc.msg}",
                              path=str(path), line=exc.lineno) from None
    calls = [node for node in ast.walk(tree)
             if isinstance(node, ast.Call) and _is_param_call(node)]
    calls.sort(key=lambda node: (node.lineno, node.col_offset))
    return calls, [_literal_arguments(call) for call in calls]


def _is_param_call(node: ast.AST) -> bool:
    if not isinstance(node, ast.Call):
        return False
    func = node.func
    return (isinstance(func, ast.Name) and func.id == "param") or (
        isinstance(func, ast.Attribute) and func.attr == "param"
    )


def _literal_arguments(call: ast.Call) -> dict[str, Any] | None:
    """The call's arguments by name when every one is a literal, else None."""
    try:
        values = {_PARAM_ARGS[i]: ast.literal_eval(arg) for i, arg in enumerate(call.args)}
        for keyword in call.keywords:
            if keyword.arg is None:
                return None
            values[keyword.arg] = ast.literal_eval(keyword.value)
    except (ValueError, TypeError, SyntaxError, IndexError):
        return None
    return values


def _specs(path: Path, calls: list[ast.Call], literal: list[Any]) -> dict[str, ParamSpec]:
    specs: dict[str, ParamSpec] = {}
    for call, args in zip(calls, literal, strict=True):
        try:
            spec = make_spec(**args)
        except (DLFLError, TypeError) as exc:
            raise InvalidArgumentError(f"{path}:{call.lineno}: {exc}") from None
        if spec.name in specs and specs[spec.name] != spec:
            raise InvalidArgumentError(f"{path}:{call.lineno}: parameter {spec.name!r} is declared "
                            "twice with different settings")
        specs[spec.name] = spec
    return specs


def _run_for_declarations(path: Path) -> dict[str, ParamSpec]:
    from .headless import run_outcome

    outcome = run_outcome(str(path))
    if outcome.error is not None:
        raise ScriptFailedError(outcome.error, f"running {path} to find its parameters "
                                f"failed: {outcome.error}")
    return outcome.declarations


def check_values(specs: dict[str, ParamSpec], values: dict[str, Any]) -> dict[str, Any]:
    """``values`` checked and converted against the declarations.

    Raises:
        InvalidArgumentError: a name the script does not declare (listing those it
            does) or a value that does not fit its declaration.
    """
    problem = undeclared(specs, values)
    if problem is not None:
        raise InvalidArgumentError(problem)
    checked = {}
    for name, value in values.items():
        checked[name] = specs[name].check(value)
    return checked


def describe(specs: Iterable[ParamSpec]) -> list[str]:
    """One line per parameter, as ``livemod params`` prints them."""
    lines = []
    for spec in specs:
        extra = []
        if spec.min is not None or spec.max is not None:
            extra.append(f"range {spec.min if spec.min is not None else '-inf'}.."
                         f"{spec.max if spec.max is not None else 'inf'}")
        if spec.step is not None:
            extra.append(f"step {spec.step}")
        if spec.choices is not None:
            extra.append("choices " + ", ".join(repr(c) for c in spec.choices))
        detail = f" ({'; '.join(extra)})" if extra else ""
        doc = f"  {spec.doc}" if spec.doc else ""
        lines.append(f"{spec.name} = {spec.default!r}  [{spec.kind}]{detail}{doc}")
    return lines


def fitting_values(specs: dict[str, ParamSpec], values: dict[str, Any],
                   previous: dict[str, ParamSpec]) -> dict[str, Any]:
    """The ``values`` that still fit ``specs`` (converted), for a script that was edited.

    A value whose declaration changed so that it no longer fits (another kind,
    a narrower range, a lost choice) is dropped, and so is one whose declaration
    was in ``previous`` but is gone now; names never declared pass through (they
    are plain globals of the script).
    """
    kept = {}
    for name, value in values.items():
        spec = specs.get(name)
        if spec is None:
            if name not in previous:
                kept[name] = value
            continue
        try:
            kept[name] = spec.check(value)
        except DLFLError:
            continue
    return kept


def undeclared(specs: dict[str, ParamSpec], values: dict[str, Any],
               ran: bool = False) -> str | None:
    """The error line for the first name in ``values`` that ``specs`` lacks, else None.

    With ``ran``, ``specs`` are what a run declared: a ``param()`` in a branch the
    run did not take is in the script but not in them, and the line says so.
    """
    for name in values:
        if name not in specs:
            known = ", ".join(specs) or "none"
            hint = did_you_mean(name, specs)
            if ran:
                return (f"the run declared no parameter {name!r}{hint} (it declared: {known}); "
                        f"a param() call declares it only when it runs (not in an if "
                        f"branch or a function that did not run)")
            return f"the script declares no parameter {name!r}{hint} (it declares: {known})"
    return None


def given_values(script: str | Path, texts: list[str]) -> dict[str, Any]:
    """``--set name=value`` texts, checked against the script's declarations when
    those are literal (read without running the script).

    When a ``param()`` call computes its arguments the texts are returned as they
    are: ``param()`` parses and checks each value during the run, and
    :func:`undeclared` says afterwards whether a name was never declared.

    Raises:
        ValueError: a text without ``=`` or with a bad name.
        InvalidArgumentError: a name the script does not declare, or a value
            that does not fit.
        FileFormatError, ScriptFailedError: as :func:`declared_parameters` says.
        OSError: the script cannot be read.
    """
    raw = {}
    for text in texts:
        name, sep, value = text.partition("=")
        if not sep or not name.isidentifier():
            raise ValueError(f"--set expects name=value, got {text!r}")
        raw[name] = value
    if not raw:
        return {}
    path = Path(script)
    specs = literal_declarations(script_source(path), path)
    return raw if specs is None else check_values(specs, raw)
