"""Compile a user script with cheap cancellation checks on its own code only.

CPython 3.11 cannot switch a tracer on in another thread, and a tracer that is
always on slows every line the worker runs (library code included). So the
runner compiles the script (never the library) with one extra test at the top
of every loop body and every function body::

    if __livemod_cancel__: __livemod_stop__()

The flag is a plain global of the run's namespace, which the controlling
thread sets when the run is cancelled; while it is False the test costs one
global load and one jump per iteration. The module body also declares both
names ``global`` (which changes nothing else), so that loops at the top level
of the script load the flag with ``LOAD_GLOBAL``, which CPython specializes,
rather than ``LOAD_NAME``, a dictionary lookup every time. ``while True: pass`` therefore stops
at its next iteration. Line numbers are those of the loop or function, so
tracebacks and step lines are unchanged.
"""

from __future__ import annotations

import ast
import io
import tokenize
from types import CodeType

CANCEL_FLAG = "__livemod_cancel__"
STOP_FUNCTION = "__livemod_stop__"


class _InsertChecks(ast.NodeTransformer):
    """Prepends the cancellation test to loop and function bodies."""

    def _check(self, node: ast.AST) -> ast.stmt:
        test = ast.If(
            test=ast.Name(id=CANCEL_FLAG, ctx=ast.Load()),
            body=[ast.Expr(ast.Call(ast.Name(id=STOP_FUNCTION, ctx=ast.Load()), [], []))],
            orelse=[],
        )
        for sub in ast.walk(test):
            ast.copy_location(sub, node)
            sub.end_lineno = node.lineno  # type: ignore[attr-defined]
        return test

    def _with_check(self, node: ast.AST) -> ast.AST:
        self.generic_visit(node)
        body = node.body  # type: ignore[attr-defined]
        at = 1 if body and _is_docstring(body[0]) else 0  # keep docstrings first
        body.insert(at, self._check(node))
        return node

    def visit_Module(self, node: ast.Module) -> ast.Module:
        self.generic_visit(node)
        body = node.body
        at = 1 if body and _is_docstring(body[0]) else 0
        while at < len(body) and _is_future_import(body[at]):
            at += 1  # both must stay first
        if at < len(body):  # else nothing runs that could check
            declare = ast.Global(names=[CANCEL_FLAG, STOP_FUNCTION])
            body.insert(at, ast.copy_location(declare, body[at]))
        return node

    visit_While = _with_check
    visit_For = _with_check
    visit_AsyncFor = _with_check
    visit_FunctionDef = _with_check
    visit_AsyncFunctionDef = _with_check


def _is_docstring(stmt: ast.stmt) -> bool:
    return (
        isinstance(stmt, ast.Expr)
        and isinstance(stmt.value, ast.Constant)
        and isinstance(stmt.value.value, str)
    )


def _is_future_import(stmt: ast.stmt) -> bool:
    return isinstance(stmt, ast.ImportFrom) and stmt.module == "__future__"


def compile_script(source: str, path: str, *, checks: bool = True) -> CodeType:
    """Compile ``source`` as the file ``path`` (so tracebacks name it).

    Args:
        source: the script's text.
        path: the script's real path, used as the code's file name.
        checks: insert the cancellation tests described in the module docstring.

    Returns:
        A module code object for ``exec``.

    Raises:
        SyntaxError: the script does not parse; nothing has run.
    """
    tree = ast.parse(source, filename=path, mode="exec")
    if checks:
        tree = _InsertChecks().visit(tree)
    return compile(tree, path, "exec", dont_inherit=True)


def read_script(path: str) -> str:
    """The text of the script at ``path``, decoded as Python decodes a source file:
    UTF-8 (a byte-order mark allowed), or the encoding a ``# -*- coding: ... -*-``
    line in the first two names.

    Raises:
        OSError: the file cannot be read.
        SyntaxError: its bytes are not text in that encoding (the line and byte
            named, as Python names them), or the coding line names no encoding.
    """
    with open(path, "rb") as handle:
        return decode_script(handle.read(), path)


def decode_script(data: bytes, path: str) -> str:
    """The bytes ``data`` of the script at ``path`` as text (see :func:`read_script`).

    Raises:
        SyntaxError: as :func:`read_script`.
    """
    try:
        encoding, _ = tokenize.detect_encoding(io.BytesIO(data).readline)
    except SyntaxError as exc:  # a bad coding line, or bytes that are not UTF-8
        _decoded(data, "utf-8", path)  # names the byte, if that is what it was
        raise SyntaxError(exc.msg, (path, 1, 1, None)) from None
    return _decoded(data, encoding, path)


def _decoded(data: bytes, encoding: str, path: str) -> str:
    """``data`` decoded, or a SyntaxError naming the first byte that is not text."""
    try:
        return data.decode(encoding)
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        name = "UTF-8" if encoding.startswith("utf-8") else encoding
        raise SyntaxError(f"byte 0x{data[exc.start]:02x} on line {line} is not {name} text: "
                          f"save the file as UTF-8, or declare its encoding on the first "
                          f"line (# -*- coding: latin-1 -*-)", (path, line, 1, None)) from None
