"""``livemod run``, ``livemod batch`` and ``livemod params``: the runner's subcommands.

The top-level ``livemod`` parser calls :func:`add_commands`; each subcommand
stores its function in ``handler``, which takes the parsed arguments and returns the
exit code. :func:`main` is a stand-alone entry point over the same parsers.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import queue
import select
import signal
import sys
import threading
from collections.abc import Callable, Sequence
from typing import Any, TextIO

from livemod.commandline import (
    DONE,
    FAILED,
    INTERRUPTED,
    USAGE,
    UsageError,
    check_readable,
    check_writable,
    describe,
    error,
    note,
    usage_errors,
)
from livemod.dlfl.analysis import summarize
from livemod.dlfl.budget import DEFAULT_FACE_BUDGET, ENVIRONMENT_VARIABLE
from livemod.dlfl.io import WRITERS, keeps_objects, scene_objects
from livemod.dlfl.io.source import show_path
from livemod.dlfl.scene import Selection

from . import declarations
from .batch import (
    BatchInterrupted,
    BatchLost,
    LiveIndex,
    Variant,
    VariantResult,
    declared_sweep,
    index_path,
    make_variants,
    run_batch,
    sweep,
)
from .headless import report_selection, run_outcome
from .recording import StepRecord
from .results import RunResult, result_mesh, save_problem

OUTPUT_SUFFIXES = tuple(f".{key}" for key in WRITERS)


def add_commands(subparsers: Any) -> None:
    """Add ``run``, ``batch`` and ``params`` to an ``argparse`` subparsers object."""
    _add_run(subparsers)
    _add_batch(subparsers)
    _add_params(subparsers)


def _add_params(subparsers: Any) -> None:
    params = subparsers.add_parser(
        "params", help="list the parameters a script declares with param()")
    params.add_argument("script", help="the Python script")
    params.set_defaults(handler=cmd_params)


def cmd_params(args: argparse.Namespace) -> int:
    """``livemod params``: print one line per declared parameter; returns 0.

    Raises:
        OSError: the script cannot be read.
        DLFLError: a malformed declaration, or the script fails when it has to be
            run to find its declarations.
    """
    check_readable(args.script)
    specs = declarations.declared_parameters(args.script)
    if not specs:
        print(f"{args.script} declares no parameters")
    for line in declarations.describe(specs.values()):
        print(line)
    return DONE


def _seed(text: str) -> int | None:
    if text.lower() == "none":
        return None
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"the seed must be a whole number or 'none', not {text!r}") from None


def whole_number_option(what: str, least: int) -> Callable[[str], int]:
    """An argparse ``type``: the text as a whole number of at least ``least``.

    The parser it returns raises ``argparse.ArgumentTypeError`` naming ``what``
    for any other text.
    """
    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            value = least - 1
        if value < least:
            raise argparse.ArgumentTypeError(
                f"{what} must be a whole number >= {least}, not {text!r}")
        return value

    return parse


_jobs = whole_number_option("jobs", 1)


def add_seed_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--seed N`` (default 0; ``none`` leaves random and numpy.random unseeded),
    the seed every run of the command starts from."""
    parser.add_argument("--seed", type=_seed, default=0,
                        help="seed of random/numpy at the start of every run (or 'none')")


class _FaceBudget(argparse.Action):
    """``--face-budget N`` sets the session's face budget through
    ``LIVEMOD_FACE_BUDGET``, which this process and the ones it starts (a
    batch's workers) read (see :mod:`livemod.dlfl.budget`)."""

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace,
                 values: Any, option_string: str | None = None) -> None:
        os.environ[ENVIRONMENT_VARIABLE] = str(values)
        setattr(namespace, self.dest, values)


def add_face_budget_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--face-budget N``: refuse any modeling operation whose result would
    pass N faces (or 4N corners), before it allocates."""
    parser.add_argument("--face-budget", type=whole_number_option("the face budget", 1),
                        action=_FaceBudget, metavar="N",
                        help="refuse operations whose result would pass N faces "
                             f"(default: ${ENVIRONMENT_VARIABLE} or {DEFAULT_FACE_BUDGET:,})")


def add_select_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--select KIND=IDS`` (repeatable), the selection ``faces(True)`` and the
    like return in the script, as the viewer's picks give it there."""
    parser.add_argument("--select", action="append", default=[], type=_select_text,
                        metavar="KIND=IDS",
                        help="what faces(True) etc. return, e.g. faces=12,31 (kinds: faces, "
                             "edges, verts, corners), repeatable; the viewer echoes its "
                             "picks in this form")


def _select_text(text: str) -> str:
    try:
        Selection.parse([text])
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    return text


def add_all_objects_option(parser: argparse.ArgumentParser) -> None:
    """``--all-objects``: write (and count) every object of the scene."""
    parser.add_argument("--all-objects", action="store_true",
                        help="write and count every object of the scene (default: the "
                             "current object): .glb, .gltf and .3mf keep each apart, as a "
                             "node or object under its name; other formats join them into "
                             "one mesh")


def selection_of(args: argparse.Namespace) -> Selection | None:
    """The selection of the ``--select`` options (checked as they were parsed), or
    None when there were none."""
    return Selection.parse(args.select) if args.select else None


def _add_run(subparsers: Any) -> None:
    run = subparsers.add_parser("run", help="run a modeling script headless (or on every save)")
    run.add_argument("script", help="the Python script")
    run.add_argument("--mesh", metavar="IN", help="mesh the script starts from (.obj .dlfl .stl .ply)")
    run.add_argument("-o", "--output", metavar="OUT", help="write the result (.obj .dlfl .stl .ply)")
    run.add_argument("--steps", action="store_true", help="print the step list")
    add_all_objects_option(run)
    add_seed_option(run)
    add_face_budget_option(run)
    run.add_argument("--set", "--param", dest="set", action="append", default=[],
                     metavar="NAME=VALUE", help="a declared script parameter, repeatable")
    add_select_option(run)
    run.add_argument("--watch", action="store_true", help="re-run (and rewrite OUT) on every save")
    run.add_argument("--poll", action="store_true", help="poll for changes (no fs events)")
    run.add_argument("--max-runs", type=int, default=None, help=argparse.SUPPRESS)
    run.set_defaults(handler=cmd_run)


def _add_batch(subparsers: Any) -> None:
    batch = subparsers.add_parser("batch", help="run parameter variants of a script in parallel")
    batch.add_argument("script", help="the Python script")
    batch.add_argument("--param", action="append", required=True,
                       metavar="NAME=START:STOP:COUNT",
                       help="a swept parameter (or NAME=a,b,c, or NAME=value), repeatable")
    batch.add_argument("--index", metavar="FILE",
                       help="the sweep's JSON index (default: index.json next to the outputs)")
    batch.add_argument("-o", "--output", metavar="PATTERN",
                       help="output file pattern, e.g. 'out/{name}_{index}.obj'")
    batch.add_argument("-j", "--jobs", type=_jobs, default=os.cpu_count() or 1,
                       help="processes to run variants on (default: one per core; with "
                            "--cluster local, the cluster's worker processes)")
    batch.add_argument("--cluster", metavar="ADDRESS",
                       help="run the variants on a Dask cluster: its scheduler's address "
                            "(tcp://host:8786) or scheduler file, or 'local' for a Dask "
                            "cluster of -j processes here (needs livemod[cluster])")
    batch.add_argument("--mesh", metavar="IN", help="mesh every variant starts from")
    add_all_objects_option(batch)
    add_seed_option(batch)
    add_face_budget_option(batch)
    add_select_option(batch)
    batch.set_defaults(handler=cmd_batch)


def check_mesh_output(path: str | None) -> None:
    """Refuse an ``-o`` mesh name no writer takes; None passes.

    Raises:
        UsageError: ``path`` does not end with a suffix of ``OUTPUT_SUFFIXES``.
    """
    if path is not None and not path.lower().endswith(OUTPUT_SUFFIXES):
        raise UsageError(f"output {show_path(path)} must end with one of "
                         f"{', '.join(OUTPUT_SUFFIXES)}")


def check_run_files(script: str, mesh: str | None, output: str | None) -> None:
    """Check what a command that runs ``script`` reads (``script``, the ``--mesh``
    file) and writes (the ``-o`` mesh), before it runs: a long run must not end
    in a bad name. None skips a check.

    Raises:
        UsageError: an output suffix no writer takes.
        OSError: a file that cannot be read, or an output that cannot be written.
    """
    check_mesh_output(output)
    check_readable(script)
    if mesh is not None:
        check_readable(mesh)
    if output is not None:
        check_writable([output])


def script_values(script: str, texts: list[str]) -> dict[str, Any]:
    """The ``--set NAME=VALUE`` texts checked against the script's declarations
    (see :func:`~livemod.runner.declarations.given_values`); {} for none.

    Raises:
        UsageError: a text that is not ``name=value``, a name the script does not
            declare, or a value that does not fit.
        DLFLError: the script's own fault (a syntax error, bytes that are not
            text, a malformed ``param()`` call), as when it runs.
        OSError: the script cannot be read.
    """
    if not texts:
        return {}
    source = declarations.script_source(script)
    declarations.literal_declarations(source, script)  # its own faults: not usage
    with usage_errors():
        return declarations.given_values(script, texts)


def cmd_run(args: argparse.Namespace) -> int:
    """``livemod run``: 0 on success, 1 when the script fails or leaves nothing to
    write, 2 for a parameter the run did not declare, 130 when interrupted.

    The output's path is resolved before the script runs (which may change the
    working directory). Threads the script leaves running do not hold the
    command up: see :func:`_end_past_script_threads`.

    Raises:
        UsageError, OSError, DLFLError: see :func:`check_run_files` and
            :func:`script_values`; all before the script runs.
    """
    check_run_files(args.script, args.mesh, args.output)
    params = script_values(args.script, args.set)
    ours = set(threading.enumerate())
    if args.watch:
        code = _watch(args, params)
    else:
        output = None if args.output is None else os.path.abspath(args.output)
        outcome = run_outcome(args.script, mesh_path=args.mesh, seed=args.seed,
                              parameters=params, selection=selection_of(args))
        code = _finish_run(args, outcome, params, output)
    _end_past_script_threads(code, ours)
    return code


def _end_past_script_threads(code: int, ours: set[threading.Thread]) -> None:
    """End the process now, with ``code``, when the script left threads running
    that Python would wait for at exit (not daemon ones, not in ``ours``): the
    command's work is done and written. A note names them. Only from the main
    thread, as the command's last act (it runs no ``atexit`` function)."""
    left = [t for t in threading.enumerate()
            if t not in ours and t.is_alive() and not t.daemon]
    if not left or threading.current_thread() is not threading.main_thread():
        return
    names = ", ".join(t.name for t in left)
    them = "them" if len(left) > 1 else "it"
    note(f"the script left {len(left)} thread{'s' if len(left) > 1 else ''} running "
         f"({names}); livemod exits without waiting for {them}")
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError):  # a reader gone: nothing to say
            stream.flush()
    os._exit(code)


def _finish_run(args: argparse.Namespace, outcome: Any, params: dict[str, Any],
                output: str | None) -> int:
    """Report a headless run (steps, error or summary) and save its mesh to
    ``output`` (absolute; ``args.output`` is how it is named); the exit code."""
    if args.steps:
        print_steps(outcome.steps)
    report_selection(outcome.run)
    problem = (declarations.undeclared(outcome.declarations, params, ran=True)
               if outcome.error is None else None)
    if problem is not None:  # only for scripts whose declarations are computed
        error(problem)
        return USAGE
    if outcome.error is not None and _script_output_went_away(outcome.error):
        raise BrokenPipeError  # `livemod run script | head`: end quietly, as for our own output
    if outcome.error is not None:
        print("\n".join(outcome.error.trace_lines()), file=sys.stderr)
        error(str(outcome.error))
        return FAILED
    mesh = result_mesh(outcome.scene, args.all_objects)
    # written before anything is printed: a reader that leaves early (`| head -1`)
    # closes our output, and OUT must not depend on it
    code = _save(scene_objects(outcome.scene, args.all_objects), output)
    print_summary(args.script, mesh, len(outcome.steps), outcome.elapsed)
    _print_objects(outcome.scene, args)
    if code == 0 and args.output is not None:
        print(f"wrote {args.output}")
    return code


def _script_output_went_away(error: Any) -> bool:
    """True when the script failed writing to our standard output because its
    reader closed the pipe (a BrokenPipeError of its own socket is an error)."""
    if not error.message.startswith("BrokenPipeError"):
        return False
    try:
        sys.stdout.flush()  # the script's unwritten output is still buffered
    except BrokenPipeError:
        return True
    except (OSError, ValueError):
        return False
    try:  # nothing was left to flush: ask the pipe (POLLERR once its reader is gone)
        poller = select.poll()
        poller.register(sys.stdout.fileno(), 0)
        return any(events & select.POLLERR for _, events in poller.poll(0))
    except (OSError, ValueError, AttributeError):  # no fileno, no poll (Windows)
        return False


def _print_objects(scene: Any, args: argparse.Namespace) -> None:
    """Say which objects the summary (and ``-o``) cover, when the scene has several."""
    count = len(scene.objects)
    if count <= 1:
        return
    covered = "the counts above and -o" if args.output else "the counts above"
    if args.all_objects and args.output and keeps_objects(args.output):
        print(f"objects: {count}, joined into one mesh for the counts above; -o keeps "
              f"them apart")
    elif args.all_objects:
        print(f"objects: {count}, joined into one mesh for {covered}")
    else:
        print(f"objects: {count} in the scene; {covered} are the current one's (object "
              f"{scene.current}; --all-objects takes them all)")


def _save(objects: Sequence[tuple[str, Any]], output: str | None) -> int:
    """Write the ``(name, mesh)`` ``objects`` to ``output`` (its folder made if
    missing), saying only what failed (on standard error); the exit code. The
    name was checked before the run, so a failure here is the disk's (full, or
    changed since)."""
    if output is None:
        return DONE
    problem = save_problem(objects, output)
    if problem is not None:
        error(problem)
        return FAILED
    return DONE


def print_summary(script: str, mesh: Any, steps: int, elapsed: float,
                  out: TextIO | None = None) -> None:
    """Counts, holes, components and genus of the result, as ``livemod run`` prints them."""
    out = out or sys.stdout
    print(f"{script}: ok, {steps} steps, {elapsed:.3f} s", file=out)
    if mesh is None:
        print("empty scene", file=out)
        return
    s = summarize(mesh)
    genera = ", ".join(str(g) for g in s.component_genera)
    per_component = f" (per component: {genera})" if s.components > 1 else ""
    print(f"V={s.vertices} E={s.edges} F={s.faces} holes={s.holes} "
          f"components={s.components} genus={s.genus}{per_component}", file=out)
    sizes = " ".join(f"{k}:{v}" for k, v in sorted(s.face_sizes.items()))
    print(f"face sizes: {sizes}", file=out)


STEPS_HEADER = (f"{'step':>5}  {'line':>5}  {'command':<20} {'V':>9} {'E':>9} {'F':>9}"
                f"  {'time':>10}  {'cumulative':>10}")


def print_steps(steps: Sequence[StepRecord], out: TextIO | None = None) -> None:
    """A header, then one line per step: its index, script line, label, the
    counts after it, the time it took and the time since the run started."""
    out = out or sys.stdout
    print(STEPS_HEADER, file=out)
    before = 0.0
    for s in steps:
        line = "?" if s.line is None else str(s.line)
        v, e, f = s.counts
        print(f"{s.index:5d}  {line:>5}  {s.label:<20} {v:9d} {e:9d} {f:9d}"
              f"  {s.elapsed - before:8.4f} s  {s.elapsed:8.4f} s", file=out)
        before = s.elapsed


def _watch(args: argparse.Namespace, params: dict[str, Any]) -> int:
    """Re-run on every save until interrupted (or ``--max-runs`` results)."""
    from .session import LiveSession

    session = LiveSession(args.script, mesh_path=args.mesh, seed=args.seed, poll=args.poll,
                          preview=False, output=args.output, parameters=params,
                          all_objects=args.all_objects)
    session.set_selection(selection_of(args))
    session.start()
    print(f"watching {session.script} (Ctrl-C to stop)", file=sys.stderr)
    seen = 0
    background: tuple[int, ...] = ()  # the runs said to go on in the background
    try:
        while args.max_runs is None or seen < args.max_runs:
            try:
                result = session.results.get(timeout=0.2)
            except queue.Empty:
                result = None
            background = _report_background(session.background_runs, background)
            if result is not None:
                seen += 1
                _report(result, args.output)
    except KeyboardInterrupt:  # the way to stop watching, but still an interruption
        return INTERRUPTED
    finally:
        session.close()
        session.join(5.0)
    return DONE


def _report_background(now: tuple[int, ...], before: tuple[int, ...]) -> tuple[int, ...]:
    """Say which runs went on in the background (they did not stop when a newer
    one started) and which of those ended since ``before``; returns ``now``."""
    for run_id in now:
        if run_id not in before:
            note(f"run {run_id} did not stop when asked; it goes on in the background, "
                 f"and its result will be discarded")
    for run_id in before:
        if run_id not in now:
            note(f"run {run_id} ended in the background")
    return now


def _report(result: RunResult, output: str | None) -> None:
    print(run_summary(result, output), flush=True,
          file=sys.stderr if result.error is not None else sys.stdout)


def run_summary(result: RunResult, output: str | None = None) -> str:
    """The one line ``run --watch`` (and ``view``) prints for a run that ended:
    ``run 3: ok, 12 steps, V=90 E=176 F=88, 0.020 s`` (with ``, wrote OUT`` when
    ``output`` is given), or ``run 3: FILE:LINE: message`` for one that failed."""
    if result.error is not None:
        return f"run {result.run_id}: {result.error}"
    v, e, f = result.arrays.counts if result.arrays is not None else (0, 0, 0)
    wrote = ""
    if output:
        wrote = f", wrote {output}" if result.arrays is not None else ", no mesh to write"
    return (f"run {result.run_id}: {result.status}, {len(result.steps)} steps, "
            f"V={v} E={e} F={f}, {result.elapsed:.3f} s{wrote}")


def cmd_batch(args: argparse.Namespace) -> int:
    """``livemod batch``: 0 when every variant succeeded, 1 otherwise (or when the
    cluster was lost), 130 when interrupted by Ctrl-C and 143 by SIGTERM (the
    index then lists the variants that finished).

    Raises:
        UsageError, OSError, DLFLError: see :func:`_batch_variants`; all before
            any variant runs. UsageError also for ``--cluster`` without Dask,
            OSError for a scheduler that cannot be reached.
    """
    specs, variants, index = _batch_variants(args)
    live = LiveIndex(index, args.script, specs, len(variants)) if index is not None else None
    if args.cluster is None:
        return _sweep(args, variants, None, live)
    from . import cluster

    try:
        cluster.require_dask()
    except cluster.DaskMissing as exc:
        raise UsageError(str(exc)) from None
    cluster.silence_dask_logs()
    with cluster.connect(args.cluster, args.jobs) as client:
        cluster.note(cluster.describe_cluster(client))
        executor = cluster.DaskVariantExecutor(client, announce=cluster.note)
        return _sweep(args, variants, executor, live)


def _sweep(args: argparse.Namespace, variants: list[Variant], executor: Any,
           live: LiveIndex | None) -> int:
    """Run the batch and report it; the exit code."""
    planned = len(variants)
    try:
        results = run_batch(variants, executor, jobs=args.jobs, on_result=live)
    except BatchInterrupted as stop:
        _report_batch(stop.results, planned, stopped="interrupted")
        _write_batch_index(live, stop.results, reason=signal.Signals(stop.signum).name)
        return 128 + stop.signum
    except BatchLost as lost:
        error(str(lost))
        _report_batch(lost.results, planned, stopped="stopped")
        _write_batch_index(live, lost.results, reason=str(lost))
        return FAILED
    failed = _report_batch(results, planned)
    if args.output is None:
        _say_nothing_was_written(args, planned)
    if _write_batch_index(live, results) != DONE:
        return FAILED
    return FAILED if failed else DONE


def _say_nothing_was_written(args: argparse.Namespace, planned: int) -> None:
    """``batch`` without ``-o``: the variants ran and were checked, and no mesh was
    kept; say how to keep them."""
    names = "_".join(f"{{{text.partition('=')[0]}}}" for text in args.param)
    print(f"ran and checked {planned} variant{'s' * (planned != 1)} but wrote no mesh: "
          f"give -o with a pattern, e.g. -o 'out/{names}.obj', to write each one")


def _batch_variants(args: argparse.Namespace,
                    ) -> tuple[dict[str, Any], list[Variant], str | None]:
    """``livemod batch``'s declarations, variants and index path, every file checked.

    Raises:
        UsageError: a ``--param`` that is malformed or does not fit the
            declarations, or outputs no writer takes or that two variants share.
        OSError: the script or ``--mesh`` cannot be read, or an output or the
            index cannot be written.
        DLFLError: a malformed declaration in the script.
    """
    check_run_files(args.script, args.mesh, None)
    specs = declarations.declared_parameters(args.script)
    with usage_errors():
        sets = sweep(declared_sweep(text, specs) for text in args.param)
        variants = make_variants(args.script, sets, args.output, mesh_path=args.mesh,
                                 seed=args.seed, selection=selection_of(args),
                                 all_objects=args.all_objects)
    outputs = [v.output for v in variants if v.output is not None]
    for output in outputs:
        check_mesh_output(output)
    index = index_path(variants, args.index)
    check_writable([*outputs, *([index] if index is not None else [])])
    return specs, variants, index


def _report_batch(results: list[VariantResult], planned: int,
                  stopped: str | None = None) -> bool:
    """Print each failed variant and the tally (of a batch ``stopped`` early, if
    that word is given); True when a variant failed."""
    failed = [r for r in results if r.status != "ok"]
    for r in failed:
        error(f"variant {r.index} {dict(r.parameters)}: {r.error}")
    ok = len(results) - len(failed)
    if stopped is not None:
        print(f"{stopped}: {len(results)}/{planned} variants finished, {ok} ok")
    else:
        print(f"{ok}/{planned} variants ok")
    return bool(failed)


def _write_batch_index(live: LiveIndex | None, results: list[VariantResult],
                       reason: str | None = None) -> int:
    """Write the batch's index (if it has one; interrupted when a ``reason`` is
    given) and say so; the exit code."""
    if live is None:
        return DONE
    try:
        live.write(results, interrupted=reason is not None, reason=reason)
    except OSError as exc:
        error(f"the index was not written: {describe(exc)}")
        return FAILED
    print(f"wrote {live.path}")
    return DONE


def main(argv: Sequence[str] | None = None) -> int:
    """Run ``livemod run``, ``batch`` or ``params`` (the ``livemod`` command line)."""
    from livemod.cli import main as livemod_main

    return livemod_main(argv)


if __name__ == "__main__":
    raise SystemExit(main())
