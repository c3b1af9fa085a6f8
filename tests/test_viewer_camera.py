"""The orbit camera (numpy only): framing, orbit, pan, zoom, presets."""

from __future__ import annotations

import numpy as np
import pytest

from livemod.viewer.camera import Camera, bounds_changed_a_lot


def test_camera_fit_holds_the_bounding_sphere_in_view() -> None:
    camera = Camera(yaw=10, pitch=20)
    bounds = np.array([[-1.0, -2.0, -3.0], [3.0, 2.0, 1.0]])
    camera.fit(bounds)
    corners = np.array([[x, y, z] for x in bounds[:, 0] for y in bounds[:, 1]
                        for z in bounds[:, 2]])
    for yaw in range(0, 360, 30):
        camera.yaw = yaw
        clip = np.c_[corners, np.ones(8)] @ camera.view_projection(1.0).T
        ndc = clip[:, :3] / clip[:, 3:]
        assert np.all(np.abs(ndc) <= 1.0)



def test_camera_orbit_pan_zoom_ortho_presets() -> None:
    camera = Camera()
    camera.fit(np.array([[-1.0, -1, -1], [1, 1, 1]]))
    distance = camera.distance
    camera.zoom(1)
    assert camera.distance == pytest.approx(0.9 * distance)
    camera.orbit(0, 500)
    assert camera.pitch < 90
    camera.preset("top")
    assert camera.eye()[1] > 0.99 * camera.distance
    before = camera.target.copy()
    camera.pan(10, 0, 100)
    assert not np.allclose(before, camera.target)
    camera.ortho = True
    assert camera.projection_matrix(1.5)[3, 3] == 1.0



def test_refit_only_on_big_bounds_changes() -> None:
    unit = np.array([[-1.0, -1, -1], [1, 1, 1]])
    assert bounds_changed_a_lot(None, unit)
    assert not bounds_changed_a_lot(unit, unit * 1.5)
    assert bounds_changed_a_lot(unit, unit * 2.5)
    assert bounds_changed_a_lot(unit, unit * 0.3)
    assert bounds_changed_a_lot(unit, unit + 10)



def test_fit_points_frames_a_whole_turntable_tightly() -> None:
    rng = np.random.default_rng(3)
    points = rng.normal(size=(500, 3)) * [0.3, 3.0, 0.3]   # tall and thin
    yaws = np.arange(0, 360, 30.0)
    for ortho in (False, True):
        camera = Camera(pitch=20, ortho=ortho)
        camera.fit_points(points, 1.5, yaws)
        widest = 0.0
        for yaw in yaws:
            camera.yaw = yaw
            clip = np.c_[points, np.ones(len(points))] @ camera.view_projection(1.5).T
            ndc = np.abs(clip[:, :2] / clip[:, 3:])
            assert ndc.max() <= 1.0
            widest = max(widest, float(ndc.max()))
        assert widest > 0.9   # tight: no loose bounding-sphere margin


def test_an_ortho_near_plane_may_lie_behind_the_eye() -> None:
    near, far = Camera(distance=0.5, scene_radius=1.0, ortho=True).clip_range()
    assert near < -1.0 and far > 1.5
    near, _ = Camera(distance=0.5, scene_radius=1.0).clip_range()
    assert near > 0.0  # a perspective one never
