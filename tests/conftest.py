"""Fixtures shared by the test modules."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from livemod.dlfl import Scene, use_scene
from livemod.dlfl.shapes import cube


@pytest.fixture
def scene() -> Iterator[Scene]:
    """A scene holding TopMod's cube as its current object, bound for the commands."""
    bound = Scene()
    bound.add(cube(), "cube")
    with use_scene(bound):
        yield bound
