"""The view state (GL-free): what compares equal draws the same overlay."""

from __future__ import annotations

from dataclasses import replace

import pytest

from livemod.dlfl import mesh_arrays
from livemod.dlfl.shapes import cube
from livemod.viewer.view_state import ViewState


def test_results_and_meshes_compare_by_identity_the_rest_by_value() -> None:
    arrays, twin = mesh_arrays(cube()), mesh_arrays(cube())
    state = ViewState(script="/x/model.py", arrays=arrays, selection=("faces(True) == (1,)",))
    assert state == replace(state, selection=("faces(True) == (1,)",))
    assert state == ViewState(script="/x/model.py", arrays=arrays,
                              selection=("faces(True) == (1,)",))
    assert state != replace(state, arrays=twin)  # equal arrays, another upload
    assert state != replace(state, fps=30.0)
    assert state.without_fps() == replace(state, fps=12.0).without_fps()
    assert state != "a state"


def test_a_state_is_compared_never_hashed() -> None:
    with pytest.raises(TypeError):
        hash(ViewState())
