"""Orbit camera: yaw about the vertical axis, pitch (tilt), distance to a target point."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np


def perspective(fov_y_deg: float, aspect: float, near: float, far: float) -> np.ndarray:
    """OpenGL perspective projection matrix (row-major numpy; transpose when uploading)."""
    f = 1.0 / math.tan(math.radians(fov_y_deg) / 2)
    m = np.zeros((4, 4))
    m[0, 0], m[1, 1] = f / aspect, f
    m[2, 2], m[2, 3] = (far + near) / (near - far), 2 * far * near / (near - far)
    m[3, 2] = -1.0
    return m


def orthographic(half: float, near: float, far: float) -> np.ndarray:
    """Symmetric orthographic projection covering [-half, half] in x and y."""
    m = np.eye(4)
    m[0, 0] = m[1, 1] = 1.0 / half
    m[2, 2], m[2, 3] = -2.0 / (far - near), -(far + near) / (far - near)
    return m


WORLD_UP = np.array([0.0, 1.0, 0.0])


def look_at(eye: np.ndarray, target: np.ndarray, up: np.ndarray = WORLD_UP) -> np.ndarray:
    """View matrix looking from ``eye`` at ``target``."""
    f = target - eye
    f = f / np.linalg.norm(f)
    if abs(float(np.dot(f, up))) > 0.999:
        up = np.array([0.0, 0.0, 1.0])
    s = np.cross(f, up)
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    m = np.eye(4)
    m[0, :3], m[1, :3], m[2, :3] = s, u, -f
    m[:3, 3] = -m[:3, :3] @ eye
    return m


@dataclass
class OrbitCamera:
    """Camera orbiting ``target``: yaw (deg, any), pitch (deg above the horizon), distance."""

    yaw: float = 30.0
    pitch: float = 12.0
    distance: float = 10.0
    target: np.ndarray = field(default_factory=lambda: np.zeros(3))
    fov_y: float = 40.0

    @property
    def eye(self) -> np.ndarray:
        """World position of the camera."""
        yaw, pitch = math.radians(self.yaw), math.radians(self.pitch)
        offset = np.array([math.sin(yaw) * math.cos(pitch), math.sin(pitch), math.cos(yaw) * math.cos(pitch)])
        return self.target + self.distance * offset

    def view(self) -> np.ndarray:
        """The view matrix."""
        return look_at(self.eye, self.target)

    def projection(self, aspect: float) -> np.ndarray:
        """The projection matrix; near/far follow the distance so depth precision stays good."""
        return perspective(self.fov_y, aspect, self.distance * 0.01, self.distance * 20.0)

    def frame_bounds(self, lo: np.ndarray, hi: np.ndarray, aspect: float = 16 / 9, fill: float = 0.85) -> None:
        """Aim at the box [lo, hi] and set the distance so it fills ``fill`` of the view."""
        self.target = (lo + hi) / 2
        ext = np.maximum(hi - lo, 1e-3)
        tan_y = math.tan(math.radians(self.fov_y) / 2)
        half_h = ext[1] / 2
        half_w = max(ext[0], ext[2]) / 2
        need = max(half_h / tan_y, half_w / (tan_y * aspect)) / fill
        self.distance = need + max(ext[0], ext[2]) / 2


def zoom_out(near: OrbitCamera, whole_lo: np.ndarray, whole_hi: np.ndarray, zoom: float, max_zoom: float,
             aspect: float) -> None:
    """Zoom ``near`` (framing one tree) out by ``zoom`` (1: as framed): the distance grows with it, and
    past 1 the view glides toward the box [whole_lo, whole_hi] (the whole garden) so that at ``max_zoom``
    it frames all of it (at least ``max_zoom`` times as far as the tree's view)."""
    if zoom <= 1.0 or max_zoom <= 1.0:
        near.distance *= zoom
        return
    whole = OrbitCamera(yaw=near.yaw, pitch=near.pitch, fov_y=near.fov_y)
    whole.frame_bounds(np.asarray(whole_lo, float), np.asarray(whole_hi, float), aspect, fill=0.8)
    t = min((zoom - 1.0) / (max_zoom - 1.0), 1.0)
    far = max(whole.distance, near.distance * max_zoom)
    near.target = near.target + (whole.target - near.target) * t
    near.distance = near.distance + (far - near.distance) * t


def project_points(camera: OrbitCamera, size: tuple[int, int], points: np.ndarray) -> np.ndarray:
    """Window pixels of many 3D points (NaN for points behind the camera)."""
    clip = np.c_[points, np.ones(len(points))] @ (camera.projection(size[0] / size[1]) @ camera.view()).T
    w = np.where(clip[:, 3] > 1e-9, clip[:, 3], np.nan)
    return np.stack([(clip[:, 0] / w * 0.5 + 0.5) * size[0], (0.5 - clip[:, 1] / w * 0.5) * size[1]], axis=1)


def project_ball(camera: OrbitCamera, size: tuple[int, int], center, radius: float) -> tuple[np.ndarray, float]:
    """Window pixel of a ball's centre and its radius in pixels (NaN when behind the camera)."""
    centre = np.asarray(center, float)
    pixels = project_points(camera, size, np.stack([centre, centre + radius * camera.view()[0, :3]]))
    return pixels[0], float(np.linalg.norm(pixels[1] - pixels[0]))


def unproject_to_plane(camera: OrbitCamera, size: tuple[int, int], x: float, y: float,
                       point: np.ndarray, normal: np.ndarray) -> np.ndarray | None:
    """The point of the plane (point, normal) under window pixel (x, y)."""
    vp = camera.projection(size[0] / size[1]) @ camera.view()
    inv = np.linalg.inv(vp)
    ndc = np.array([2 * x / size[0] - 1, 1 - 2 * y / size[1]])
    near = inv @ np.array([*ndc, -1.0, 1.0])
    far = inv @ np.array([*ndc, 1.0, 1.0])
    a, b = near[:3] / near[3], far[:3] / far[3]
    d = b - a
    denom = float(d @ normal)
    if abs(denom) < 1e-12:
        return None
    s = float((point - a) @ normal) / denom
    return a + s * d if s > 0 else None

