"""An orbit camera around a target with the Y axis up (numpy only).

The camera is ``distance`` away from ``target`` at ``yaw`` (around Y) and ``pitch``
(above the XZ plane), in degrees. Orthographic views use the half-height the
perspective frustum has at the target, so toggling ortho keeps the apparent size.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

PRESET_VIEWS: dict[str, tuple[float, float]] = {
    "front": (0.0, 0.0),
    "back": (180.0, 0.0),
    "side": (90.0, 0.0),
    "top": (0.0, 89.9),
    "bottom": (0.0, -89.9),
    "iso": (45.0, 35.264),
}


@dataclass
class Camera:
    """Orbit camera state; everything else is derived.

    Attributes:
        target: ``(3,)`` float64 point looked at.
        distance: eye-to-target distance (> 0).
        yaw: degrees around +Y; 0 looks from +Z toward -Z.
        pitch: degrees above the horizon, kept inside (-90, 90).
        fov: vertical field of view in degrees (perspective).
        ortho: orthographic projection when True.
        scene_radius: radius of the framed scene, used for the clip planes.
    """

    target: np.ndarray = field(default_factory=lambda: np.zeros(3))
    distance: float = 5.0
    yaw: float = 30.0
    pitch: float = 25.0
    fov: float = 35.0
    ortho: bool = False
    scene_radius: float = 1.0

    def copy(self) -> Camera:
        """An independent copy (the target array is copied too)."""
        return replace(self, target=np.array(self.target, dtype=np.float64))

    def eye(self) -> np.ndarray:
        """``(3,)`` float64 eye position."""
        yaw, pitch = math.radians(self.yaw), math.radians(self.pitch)
        direction = np.array([
            math.cos(pitch) * math.sin(yaw), math.sin(pitch), math.cos(pitch) * math.cos(yaw)
        ])
        return np.asarray(self.target, dtype=np.float64) + self.distance * direction

    def basis(self) -> np.ndarray:
        """``(3, 3)`` rows: camera right, up and back (toward the eye) in world space."""
        back = self.eye() - self.target
        back /= np.linalg.norm(back)
        right = np.cross([0.0, 1.0, 0.0], back)
        right /= max(float(np.linalg.norm(right)), 1e-12)
        return np.stack([right, np.cross(back, right), back])

    def view_matrix(self) -> np.ndarray:
        """``(4, 4)`` float64 world-to-view matrix (column vectors)."""
        rot = self.basis()
        view = np.eye(4)
        view[:3, :3] = rot
        view[:3, 3] = -rot @ self.eye()
        return view

    def clip_range(self) -> tuple[float, float]:
        """``(near, far)`` enclosing the scene sphere (``scene_radius`` around the
        target, doubled for margin) from the current eye.

        An orthographic view's near plane may lie behind the eye: zooming it in
        moves the eye toward the target, into the mesh, while the picture only
        scales, so what is between the eye and the scene's front must still show.
        A perspective one must stay in front of the eye.
        """
        reach = 2.0 * self.scene_radius
        far = self.distance + reach + 1e-3
        if self.ortho:
            return self.distance - reach - 1e-3, far
        return max(self.distance - reach, far * 1e-4), far

    def half_height(self) -> float:
        """Half the view height at the target (the orthographic scale)."""
        return self.distance * math.tan(math.radians(self.fov) / 2.0)

    def projection_matrix(self, aspect: float) -> np.ndarray:
        """``(4, 4)`` float64 projection for a width/height ``aspect``."""
        near, far = self.clip_range()
        proj = np.zeros((4, 4))
        if self.ortho:
            h = self.half_height()
            proj[0, 0], proj[1, 1] = 1.0 / (h * aspect), 1.0 / h
            proj[2, 2], proj[2, 3] = -2.0 / (far - near), -(far + near) / (far - near)
            proj[3, 3] = 1.0
            return proj
        f = 1.0 / math.tan(math.radians(self.fov) / 2.0)
        proj[0, 0], proj[1, 1] = f / aspect, f
        proj[2, 2], proj[2, 3] = (far + near) / (near - far), 2.0 * far * near / (near - far)
        proj[3, 2] = -1.0
        return proj

    def view_projection(self, aspect: float) -> np.ndarray:
        """``(4, 4)`` float64 world-to-clip matrix."""
        return self.projection_matrix(aspect) @ self.view_matrix()

    # -- interaction ---------------------------------------------------------

    def orbit(self, dx_degrees: float, dy_degrees: float) -> None:
        """Turn around the target; pitch stops short of the poles."""
        self.yaw = (self.yaw - dx_degrees) % 360.0
        self.pitch = float(np.clip(self.pitch + dy_degrees, -89.9, 89.9))

    def pan(self, dx_pixels: float, dy_pixels: float, viewport_height: int) -> None:
        """Move the target in the view plane so the scene follows the mouse."""
        per_pixel = 2.0 * self.half_height() / max(viewport_height, 1)
        right, up, _ = self.basis()
        self.target = self.target - per_pixel * (dx_pixels * right - dy_pixels * up)

    def toggle_ortho(self) -> None:
        """Orthographic after perspective and back (the apparent size stays)."""
        self.ortho = not self.ortho

    def pose(self) -> tuple:
        """Everything the view depends on, as a value: two equal poses see the same."""
        return (tuple(self.target.tolist()), self.distance, self.yaw, self.pitch, self.fov,
                self.ortho)

    def zoom(self, steps: float) -> None:
        """Move toward (steps > 0) or away from the target, 10% per step."""
        self.distance = float(np.clip(self.distance * 0.9**steps, 1e-6, 1e9))

    def fit(self, bounds: np.ndarray, margin: float = 1.08) -> None:
        """Frame the ``(2, 3)`` ``bounds`` from the current direction.

        Raises:
            ValueError: ``bounds`` are not finite (the camera is left as it was).
        """
        bounds = np.asarray(bounds, dtype=np.float64)
        if not np.isfinite(bounds).all():
            raise ValueError(f"cannot frame bounds that are not finite: {bounds.tolist()}")
        radius = max(float(np.linalg.norm(bounds[1] - bounds[0])) / 2.0, 1e-6)
        self.target = bounds.mean(axis=0)
        self.scene_radius = radius
        self.distance = margin * radius / math.sin(math.radians(self.fov) / 2.0)

    def fit_points(self, points: np.ndarray, aspect: float, yaws: np.ndarray | None = None,
                   margin: float = 1.06) -> None:
        """Frame ``(n, 3)`` ``points`` tightly, from every yaw in ``yaws`` at once.

        The target is the centre of the points' bounding box; the distance is the
        smallest that keeps every point inside the view (width/height ``aspect``)
        at each yaw (the current yaw when None), times ``margin``. A turntable
        passes all its yaws, so one distance frames the whole orbit. Points that
        are not finite (NaN or inf) are left out; with none left (or none given)
        the camera is left as it was.
        """
        points = np.asarray(points, dtype=np.float64)
        points = points[np.isfinite(points).all(axis=1)]
        if len(points) == 0:
            return
        self.fit(np.stack([points.min(axis=0), points.max(axis=0)]))
        tan_y = math.tan(math.radians(self.fov) / 2.0)
        needed = 0.0
        for yaw in [self.yaw] if yaws is None else list(yaws):
            turned = replace(self, yaw=float(yaw))
            right, up, back = turned.basis()
            rel = points - self.target
            x, y, z = rel @ right, rel @ up, rel @ back
            depth = 0.0 if self.ortho else z  # perspective: nearer points spread more
            needed = max(needed, float(np.max(depth + np.abs(y) / tan_y)),
                         float(np.max(depth + np.abs(x) / (tan_y * aspect))))
        self.distance = max(margin * needed, 1e-6)

    def preset(self, name: str) -> None:
        """Look from one of :data:`PRESET_VIEWS` (raises KeyError if unknown)."""
        self.yaw, self.pitch = PRESET_VIEWS[name]


def bounds_changed_a_lot(old: np.ndarray | None, new: np.ndarray, factor: float = 2.0) -> bool:
    """True when ``new`` bounds should re-fit the camera: no old bounds, or a size
    change by more than ``factor`` either way, or a centre moved by more than the size."""
    if old is None:
        return True
    old_size = max(float(np.linalg.norm(old[1] - old[0])), 1e-9)
    new_size = max(float(np.linalg.norm(new[1] - new[0])), 1e-9)
    ratio = new_size / old_size
    moved = float(np.linalg.norm(new.mean(axis=0) - old.mean(axis=0)))
    return ratio > factor or ratio < 1.0 / factor or moved > max(old_size, new_size)
