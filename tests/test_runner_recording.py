"""The step hook and StepList: lines, counts and records as a plain reference says."""

from __future__ import annotations

import _thread
import contextvars
import dis
import gc
import pickle
import sys
import textwrap
import threading
import time
from types import CodeType

import pytest

from livemod.dlfl import DLFLError, Mesh, current_scene
from livemod.dlfl.commands._base import modeling_command
from livemod.dlfl.run_context import RunContext, use_run
from livemod.dlfl.scene import Scene, use_scene
from livemod.runner import RunControl, StepRecord, execute
from livemod.runner.execute import script_namespace
from livemod.runner.instrument import CANCEL_FLAG, compile_script
from livemod.runner.playback import Playback
from livemod.runner.recording import STEP_FIELDS, StepList, StepLog, StepRecorder

HELPER = '''\
import contextlib

from livemod.dlfl import createVertex, current_run, step
from livemod.dlfl.run_context import announce_step


def ring(n):
    for i in range(n):
        createVertex((i, 0, 0))


def points(n):
    for i in range(n):
        createVertex((0, i, 0))
        yield i


def call_back(fn):
    createVertex((9, 9, 9))
    fn()


@contextlib.contextmanager
def grouped(label):
    """The commands in the block are one step, announced as the block ends."""
    run = current_run()
    run.command_depth += 1
    try:
        yield
    finally:
        run.command_depth -= 1
    announce_step(label)
'''

SCRIPT = '''\
"""Commands called every way a script can call them."""
from __future__ import annotations

import helper_rec
from livemod.dlfl import current_scene


def one(x):
    createVertex((x, 1, 0))


def two(x):
    one(x)
    createVertex((x, 2, 0))


def gen(n):
    for i in range(n):
        createVertex((i, 3, 0))
        yield i


for i in range(3):
    createVertex((i, 0, 0))
    two(i)
    helper_rec.ring(2)
    helper_rec.call_back(lambda: createVertex((0, 0, 5)))
    one(i) if i % 2 else helper_rec.ring(1)
for k in gen(2):
    createVertex((k, 4, 0))
for k in helper_rec.points(2):
    one(k)
total = sum(helper_rec.points(2))
[createVertex((j, 5, 0)) for j in range(2)]
list(map(createVertex, [(0, 6, 0), (1, 6, 0)]))
step("marked")
with helper_rec.grouped("grouped"):
    createVertex((0, 7, 0))
'''


def reference_hook(run: RunContext, scene: Scene, script: str, seen: list) -> None:
    """A step hook the obvious way: walk to the script's frame, ask f_lineno and counts()."""

    def hook(label: str) -> None:
        frame = sys._getframe(1)
        while frame is not None and frame.f_code.co_filename != script:
            frame = frame.f_back
        obj = scene.objects.get(scene.current)  # type: ignore[arg-type]
        counts = obj.mesh.counts() if obj is not None else (0, 0, 0)
        seen.append((label, None if frame is None else frame.f_lineno, counts))

    run.step_hook = hook


def write(tmp_path, name: str, text: str) -> str:
    path = tmp_path / name
    path.write_text(textwrap.dedent(text), encoding="utf-8")
    return str(path)


def reference_steps(path: str) -> list:
    """(label, line, counts) of each step of the script at ``path``, by reference_hook."""
    with open(path, encoding="utf-8") as handle:
        code = compile_script(handle.read(), path)
    run, scene, seen = RunContext(), Scene(), []
    reference_hook(run, scene, path, seen)
    sys.path.insert(0, str(path).rsplit("/", 1)[0])
    try:
        with use_scene(scene), use_run(run):
            exec(code, script_namespace(path, None))  # noqa: S102
    finally:
        sys.path.pop(0)
        sys.modules.pop("helper_rec", None)
    return seen


def test_lines_and_counts_match_the_reference_for_every_way_of_calling(tmp_path):
    write(tmp_path, "helper_rec.py", HELPER)
    path = write(tmp_path, "calls.py", SCRIPT)
    outcome = execute(path)
    assert outcome.status == "ok", outcome.error
    got = [(s.label, s.line, s.counts) for s in outcome.steps]
    assert got == reference_steps(path)
    # every calling line shows up: script functions (9, 14), a script generator (19),
    # helper modules (26, 31, 33), a callback (27), comprehension, map, step(), with
    assert {line for _, line, _ in got} == {9, 14, 19, 24, 26, 27, 28, 30, 31, 33, 34, 35, 36, 37}


def test_line_of_a_script_function_called_where_a_helper_was_called_before(tmp_path):
    # same depth below the loop's frame both times: only the innermost script frame is right
    write(tmp_path, "helper_rec.py", HELPER)
    path = write(tmp_path, "depth.py", """\
        import helper_rec

        def mine():
            createVertex((0, 0, 0))

        for i in range(2):
            helper_rec.ring(1)
            mine()
        """)
    outcome = execute(path)
    assert [s.line for s in outcome.steps] == [7, 4, 7, 4]


def test_helper_generator_driven_from_two_lines_reports_each_line(tmp_path):
    write(tmp_path, "helper_rec.py", HELPER)
    path = write(tmp_path, "gens.py", """\
        import helper_rec

        it = helper_rec.points(4)
        next(it)
        next(it)
        for _ in it:
            pass
        """)
    outcome = execute(path)
    assert [s.line for s in outcome.steps] == [4, 5, 6, 6]


def test_counts_follow_the_current_object_through_switch_and_kill(tmp_path):
    path = write(tmp_path, "objects.py", """\
        createVertex((0, 0, 0))
        load("cube")
        switch(0)
        createVertex((1, 0, 0))
        kill(0)
        step("cube is current")
        deleteEdge(edges()[0])
        kill(1)
        step("empty")
        """)
    outcome = execute(path)
    assert outcome.status == "ok", outcome.error
    assert [(s.label, s.counts) for s in outcome.steps] == [
        ("createVertex", (1, 0, 1)), ("load cube", (8, 12, 6)), ("createVertex", (2, 0, 2)),
        ("cube is current", (8, 12, 6)), ("deleteEdge", (8, 11, 5)), ("empty", (0, 0, 0))]


def test_steps_are_the_records_they_always_were(tmp_path):
    path = write(tmp_path, "plain.py", "for i in range(3):\n    createVertex((i, 0, 0))\n")
    steps = execute(path).steps
    first = steps[0]
    assert isinstance(first, StepRecord)
    assert (first.index, first.label, first.line, first.counts) == (0, "createVertex", 2, (1, 0, 1))
    assert 0.0 <= first.elapsed <= steps[-1].elapsed
    records = tuple(steps)
    assert steps == records and records == tuple(steps) and hash(steps) == hash(records)
    assert steps[-1] == records[2] and steps[1:] == records[1:] and list(reversed(steps))[0] == records[2]
    assert pickle.loads(pickle.dumps(steps)) == records
    with pytest.raises(IndexError):
        steps[3]
    assert StepList([], 0, 0.0) == () and steps != records[:2]


def test_a_view_of_the_steps_keeps_its_length_while_the_run_goes_on():
    scene = Scene()
    recorder = StepRecorder("/virtual/script.py", scene, None)
    recorder.run.step_hook = recorder.hook
    with use_scene(scene), use_run(recorder.run):
        from livemod.dlfl import createVertex

        createVertex((0, 0, 0))
        early = recorder.steps
        createVertex((1, 0, 0))
    assert len(early) == 1 and len(recorder.steps) == 2
    assert early[0] == recorder.steps[0] and early[0].line is None  # not called from the script


def test_the_run_does_not_keep_a_script_frame_alive(tmp_path):
    path = write(tmp_path, "frames.py", """\
        import weakref
        from livemod.dlfl import current_run

        class Big:
            pass

        def make():
            big = Big()
            current_run().parameters["big"] = weakref.ref(big)
            createVertex((0, 0, 0))

        make()
        """)
    control = RunControl()
    outcome = execute(path, control=control)
    gc.collect()
    assert outcome.status == "ok" and outcome.run.parameters["big"]() is None


def test_top_level_loops_read_the_cancel_flag_as_a_global():
    source = '"""doc"""\nfrom __future__ import annotations\nfor i in range(2):\n    pass\n'
    code = compile_script(source, "/virtual/loop.py")
    loads = [(i.opname, i.argval) for i in dis.get_instructions(code) if i.argval == CANCEL_FLAG]
    assert loads == [("LOAD_GLOBAL", CANCEL_FLAG)]
    namespace = script_namespace("/virtual/loop.py", None)
    exec(code, namespace)  # noqa: S102  (docstring and __future__ import still come first)
    assert namespace["__doc__"] == "doc"


def hook_calls(run) -> int:
    """How many times ``run()`` calls a runner step hook (counted by a profiler)."""
    hook_code = next(c for c in StepRecorder._make_hooks.__code__.co_consts
                     if isinstance(c, CodeType) and c.co_name == "hook")
    calls = 0

    def profile(frame, event, arg) -> None:
        nonlocal calls
        calls += event == "call" and frame.f_code is hook_code

    sys.setprofile(profile)
    try:
        run()
    finally:
        sys.setprofile(None)
    return calls


def test_the_wrapper_records_what_the_hook_records_and_leaves_it_the_new_callers(tmp_path):
    write(tmp_path, "helper_rec.py", HELPER)
    path = write(tmp_path, "calls.py", SCRIPT)
    runs = []
    for control in (None, RunControl(Playback())):  # a run that may pause: the hook records all
        outcome = execute(path, control=control)
        runs.append([(s.index, s.label, s.line, s.counts) for s in outcome.steps])
    assert runs[0] == runs[1] and len(runs[0]) == 40
    loop = write(tmp_path, "loop.py", "for i in range(50):\n    createVertex((i, 0, 0))\n")
    assert hook_calls(lambda: execute(loop)) == 1  # the first step: the caller is new
    assert hook_calls(lambda: execute(loop, control=RunControl(Playback()))) == 50


@pytest.mark.timeout(60)
def test_a_cancel_stops_steps_the_wrapper_records(tmp_path):
    # the helper's loop has no compiled-in check: only the steps can stop it
    write(tmp_path, "helper_spin.py", "from livemod.dlfl import createVertex\n\n\n"
          "def ring(n):\n    for i in range(n):\n        createVertex((i, 0, 0))\n")
    path = write(tmp_path, "spin.py", "import helper_spin\nhelper_spin.ring(10 ** 8)\n")
    control = RunControl()
    threading.Timer(0.2, control.cancel).start()
    outcome = execute(path, control=control)
    assert outcome.status == "cancelled" and 0 < len(outcome.steps) < 10 ** 8
    assert outcome.error is not None and outcome.error.line == 2  # the script's line
    early = RunControl()
    early.cancel()  # before the run starts, so before the recorder is attached
    outcome = execute(path, control=early)
    assert outcome.status == "cancelled" and len(outcome.steps) == 0


def test_a_command_with_no_python_caller_is_recorded_without_a_line():
    scene = Scene()
    recorder = StepRecorder("/virtual/script.py", scene, None)
    recorder.install()
    with use_scene(scene), use_run(recorder.run):
        context = contextvars.copy_context()
    from livemod.dlfl import createVertex

    # the wrapper is the bottom frame of the new thread: no frame called it
    _thread.start_new_thread(context.run, (createVertex, (0, 0, 0)))
    deadline = time.monotonic() + 10
    while recorder.step_count() == 0 and time.monotonic() < deadline:
        time.sleep(0.01)
    recorder.release()
    steps = recorder.steps
    assert [(s.label, s.line, s.counts) for s in steps] == [("createVertex", None, (1, 0, 1))]


def test_the_lean_hook_records_a_seen_caller_and_gives_the_others_to_the_full_hook():
    scene = Scene()
    recorder = StepRecorder(__file__, scene, None)  # this file stands for the script
    recorder.install()
    from livemod.dlfl import createVertex

    def three() -> None:
        createVertex((0, 0, 0))  # a new caller: the full hook
        createVertex((1, 0, 0))  # the same caller: the lean hook
        (lambda: createVertex((2, 0, 0)))()  # another caller: the full hook

    with use_scene(scene), use_run(recorder.run):
        assert hook_calls(three) == 2
    first = three.__code__.co_firstlineno
    assert [(s.label, s.line, s.counts) for s in recorder.steps] == [
        ("createVertex", first + 1, (1, 0, 1)), ("createVertex", first + 2, (2, 0, 2)),
        ("createVertex", first + 3, (3, 0, 3))]
    recorder.release()
    assert recorder.run.step_hook is None


@modeling_command
def _drop_current() -> None:
    sc = current_scene()
    sc.kill(sc.current)  # type: ignore[arg-type]


def test_a_step_counts_nothing_when_no_object_is_left():
    scene = Scene()
    scene.add(Mesh())
    recorder = StepRecorder(__file__, scene, None)
    recorder.install()
    with use_scene(scene), use_run(recorder.run):
        _drop_current()
        with pytest.raises(DLFLError):
            _drop_current()  # nothing to kill: fails, records no step
    assert scene.current is None
    assert [(s.label, s.counts) for s in recorder.steps] == [("_drop_current", (0, 0, 0))]


def test_a_step_log_tells_each_step_s_code():
    log = StepLog()
    first, second = test_steps_are_the_records_they_always_were.__code__, write.__code__
    log.follow(None, None, first)
    log.facts.extend([0] * 2 * STEP_FIELDS)  # two steps with `first`
    log.follow(object(), None, first)  # another caller, same code: no change
    log.facts.extend([0] * STEP_FIELDS)
    log.follow(None, None, second)
    log.facts.extend([0] * STEP_FIELDS)
    assert [log.code_of(k) for k in range(4)] == [first, first, first, second]
    assert len(log) == 4 and StepLog().code_of(0) is None
