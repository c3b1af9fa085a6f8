"""RunSupervisor through a live session: what a run leaves behind once it ended."""

from __future__ import annotations

import gc
import weakref

import pytest

from livemod.runner import LiveSession, ManualNotifier, RunResult

from .runner_scripts.support import closing_session, next_result, wait_until

KEEP_SCENE = ("import weakref\nfrom livemod.dlfl import current_scene\n"
              "createVertex((0, 0, 0))\nscenes.append(weakref.ref(current_scene()))\n")


def is_ok(r: RunResult) -> bool:
    return r.status == "ok"


@pytest.mark.timeout(60)
def test_an_ended_runs_scene_is_freed_without_the_garbage_collector(tmp_path):
    script = tmp_path / "model.py"
    script.write_text(KEEP_SCENE)
    scenes: list[weakref.ref] = []  # a plain global of the script (declared by no param())
    live = LiveSession(str(script), notifier=ManualNotifier(), preview=False,
                       parameters={"scenes": scenes})
    gc.disable()  # a scene kept in a reference cycle would stay
    try:
        with closing_session(live):
            live.start()
            first = next_result(live, is_ok)
            live.reload()
            assert next_result(live, is_ok).run_id == first.run_id + 1
            wait_until(lambda: live.activity is None)
            assert len(scenes) == 2
            wait_until(lambda: scenes[0]() is None)  # run 1 is no longer the current run
            assert scenes[1]() is None  # its run ended: nothing refers to it any more
    finally:
        gc.enable()
