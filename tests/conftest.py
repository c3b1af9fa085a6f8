"""Fixtures shared by the test modules."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from livemod.dlfl import RunContext, Scene, use_run, use_scene
from livemod.dlfl.shapes import cube
from tests.topmod_samples import write_samples


@pytest.fixture
def run() -> Iterator[RunContext]:
    """A fresh run context, bound for the commands (as a run of the runner binds
    one): what they report goes here, not to the process-wide one."""
    with use_run(RunContext()) as bound:
        yield bound


@pytest.fixture
def scene(run: RunContext) -> Iterator[Scene]:
    """A scene holding TopMod's cube as its current object, bound for the commands
    (with the fresh :func:`run` context)."""
    bound = Scene()
    bound.add(cube(), "cube")
    with use_scene(bound):
        yield bound


@pytest.fixture(scope="session")
def topmod_samples(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A folder holding a stand-in for each of TopMod's sample OBJ files under the
    sample's name (``cube.obj`` ...; :mod:`tests.topmod_samples` says what each is)."""
    return write_samples(tmp_path_factory.mktemp("topmod-objs"))


# the size of the offscreen target the viewer tests share (their pixel checks use it)
OFFSCREEN_SIZE = (160, 120)


@pytest.fixture(scope="module")
def shared_offscreen() -> Iterator[Any]:
    """One EGL offscreen target (:class:`livemod.viewer.headless.Offscreen`, 160 x 120,
    no MSAA) per test module: making a context is the slow part."""
    from livemod.viewer.headless import Offscreen

    target = Offscreen(OFFSCREEN_SIZE, samples=0)
    yield target
    target.release()


@pytest.fixture
def offscreen(shared_offscreen: Any) -> Iterator[Any]:
    """The module's target, its context current (a viewer or a ``livemod render`` in
    another test made contexts of its own) and its selection empty."""
    from livemod.dlfl.scene import Selection

    shared_offscreen.activate()
    shared_offscreen.renderer.set_selection(Selection())
    yield shared_offscreen
