"""Regions of interest for editing a tree (Onishi et al. 2003 section 4.2): a sphere, or a supertoroid fitted
to two contour strokes; rules applied only inside a region; pruning a subtree.

Eq. 3 (supertoroid, with the slopes b_x, b_z of its axis):
    x(u, v) = a_x (alpha_x + cos^n u) cos^e v + b_x
    y(u, v) = a_y sin^n u + alpha_y
    z(u, v) = a_z (alpha_z + cos^n u) sin^e v + b_z,   -pi <= u <= pi, -pi/2 <= v <= pi/2
with signed powers (c^n = sign(c) |c|^n). Here b_x and b_z grow linearly with height (b = b0 + slope
(y - alpha_y)), so the region can lean like the outline that was drawn.

x and z are the region's own axes: ``yaw`` turns them about the vertical like an OrbitCamera's yaw, so a
region fitted to outlines drawn in a view has its width a_x across that view (x = the view's right,
(cos yaw, 0, -sin yaw)) and its depth a_z along the line of sight (z = (sin yaw, 0, cos yaw), toward the
camera). The centre (b_x, alpha_y, b_z) is in world coordinates; the slopes lean along the region's axes.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from arbor.engine.geometry.turtle import INITIAL_FRAME
from arbor.engine.lsystem import brackets
from arbor.engine.lsystem.lstring import LString, concat, parse_lstring

FLAT_DEPTH = 1.0  # outlines drawn on a plane carry no depth: the region is this deep for its width (round)


@dataclass(frozen=True)
class Sphere:
    """A ball: centre and radius (placed with the pointer)."""

    center: tuple[float, float, float]
    radius: float

    def contains(self, points: np.ndarray) -> np.ndarray:
        """Which points lie inside."""
        return np.linalg.norm(np.asarray(points, float) - np.asarray(self.center), axis=-1) <= self.radius


def _axes(yaw: float) -> tuple[np.ndarray, np.ndarray]:
    """The world directions of a region's x (width) and z (depth) axes for a yaw in degrees: those of an
    OrbitCamera's right and of the way back toward it."""
    t = np.radians(yaw)
    return np.array([np.cos(t), 0.0, -np.sin(t)]), np.array([np.sin(t), 0.0, np.cos(t)])


def view_yaw(across) -> float:
    """The yaw (degrees) whose x axis is the horizontal direction ``across`` (a view's right)."""
    across = np.asarray(across, float)
    return float(np.degrees(np.arctan2(-across[2], across[0])) % 360.0)


@dataclass(frozen=True)
class Supertoroid:
    """Eq. 3's supertoroid; alpha_x = alpha_z = 0 gives a (leaning) superellipsoid crown. ``yaw`` (degrees)
    turns its x and z axes about the vertical (0: world x and z; see the module docstring)."""

    a_x: float
    a_y: float
    a_z: float
    alpha_y: float
    n: float = 1.0
    e: float = 1.0
    alpha_x: float = 0.0
    alpha_z: float = 0.0
    b_x: float = 0.0
    b_z: float = 0.0
    slope_x: float = 0.0
    slope_z: float = 0.0
    yaw: float = 0.0

    def surface(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        """Points of the surface at parameters (u, v) (for drawing and tests); v = 0 is the region's +x
        side (the right outline of the view it was drawn in), v = pi its -x side."""
        def spow(c, p):
            return np.sign(c) * np.abs(c) ** p

        y = self.a_y * spow(np.sin(u), self.n) + self.alpha_y
        ring = spow(np.cos(u), self.n)
        x = self.a_x * (self.alpha_x + ring) * spow(np.cos(v), self.e) + self.slope_x * (y - self.alpha_y)
        z = self.a_z * (self.alpha_z + ring) * spow(np.sin(v), self.e) + self.slope_z * (y - self.alpha_y)
        ex, ez = _axes(self.yaw)
        return (np.array([self.b_x, 0.0, self.b_z]) + x[..., None] * ex + z[..., None] * ez
                + y[..., None] * np.array([0.0, 1.0, 0.0]))

    @property
    def center(self) -> tuple[float, float, float]:
        """The middle of the region (where an empty region starts a new axis)."""
        return (self.b_x, self.alpha_y, self.b_z)

    def contains(self, points: np.ndarray) -> np.ndarray:
        """Inside test: at each height the cross-section is a superellipse (minus the hole, if any)."""
        p = np.asarray(points, float).reshape(-1, 3)
        s = (p[:, 1] - self.alpha_y) / self.a_y
        within = np.abs(s) <= 1.0
        c = np.clip(1.0 - np.abs(s) ** (2.0 / self.n), 0.0, 1.0) ** (self.n / 2.0)
        ex, ez = _axes(self.yaw)
        off = p - np.array([self.b_x, 0.0, self.b_z])
        dx = off @ ex - self.slope_x * (p[:, 1] - self.alpha_y)
        dz = off @ ez - self.slope_z * (p[:, 1] - self.alpha_y)

        def inside_ellipse(rx, rz):
            rx, rz = np.maximum(rx, 1e-12), np.maximum(rz, 1e-12)
            return (np.abs(dx) / rx) ** (2.0 / self.e) + (np.abs(dz) / rz) ** (2.0 / self.e) <= 1.0

        outer = inside_ellipse(self.a_x * (self.alpha_x + c), self.a_z * (self.alpha_z + c))
        hole_x, hole_z = self.a_x * (self.alpha_x - c), self.a_z * (self.alpha_z - c)
        hole = (hole_x > 0) & (hole_z > 0) & inside_ellipse(hole_x, hole_z)
        return within & outer & ~hole


def fit_supertoroid(left: np.ndarray, right: np.ndarray, across=(1.0, 0.0, 0.0)) -> Supertoroid:
    """Fit eq. 3 to two contour strokes drawn as the left and right outline of a crown.

    ``across`` is the horizontal direction the outlines' widths are measured along: the right of the
    view they were drawn in (a mouse or finger draws on a vertical plane facing the camera, so the
    width lies across the view; world x, the default, suits a 3D tracker). The region's x axis is
    turned to it (its yaw). The axis runs through the midpoints of the two outlines at each height (a
    straight line: b and slope), the outlines' height range gives a_y and alpha_y, and n is the
    exponent whose profile a_x (1 - |s|^(2/n))^(n/2) fits the half-widths best (a_x by least squares
    for each n, so hand jitter averages out). Outlines drawn in 3D also give the depth a_z and the
    cross-section's exponent e (see _with_depth); outlines drawn on a plane carry no depth, and then
    a_z = FLAT_DEPTH * a_x (a round crown).
    """
    yaw = view_yaw(across)
    ex, ez = _axes(yaw)
    to_local = np.stack([ex, np.array([0.0, 1.0, 0.0]), ez], axis=1)  # world point @ it: (x, y, z) local
    left, right = np.asarray(left, float) @ to_local, np.asarray(right, float) @ to_local
    lo = max(left[:, 1].min(), right[:, 1].min())
    hi = min(left[:, 1].max(), right[:, 1].max())
    if hi <= lo:
        raise ValueError("the two outlines must overlap in height")
    ys = np.linspace(lo, hi, 48)
    order_l, order_r = np.argsort(left[:, 1]), np.argsort(right[:, 1])
    xl = np.interp(ys, left[order_l, 1], left[order_l, 0])
    xr = np.interp(ys, right[order_r, 1], right[order_r, 0])
    zl = np.interp(ys, left[order_l, 1], left[order_l, 2])
    zr = np.interp(ys, right[order_r, 1], right[order_r, 2])
    alpha_y, a_y = (lo + hi) / 2, (hi - lo) / 2
    mid_x, mid_z, half = (xl + xr) / 2, (zl + zr) / 2, np.abs(xr - xl) / 2
    slope_x, b_x = np.polyfit(ys - alpha_y, mid_x, 1)
    slope_z, b_z = np.polyfit(ys - alpha_y, mid_z, 1)
    a_x, n = _profile_fit((ys - alpha_y) / a_y, half)
    region = Supertoroid(a_x=a_x, a_y=a_y, a_z=FLAT_DEPTH * a_x, alpha_y=alpha_y, n=n, b_x=float(b_x),
                         b_z=float(b_z), slope_x=float(slope_x), slope_z=float(slope_z))
    region = _with_depth(region, np.concatenate([left, right]))
    centre = region.b_x * ex + region.b_z * ez
    return replace(region, b_x=float(centre[0]), b_z=float(centre[2]), yaw=yaw)


def _profile_fit(s: np.ndarray, half: np.ndarray) -> tuple[float, float]:
    """The scale a_x and exponent n whose profile a_x (1 - |s|^(2/n))^(n/2) is nearest the half-widths
    ``half`` at heights ``s`` (-1..1) in the least-squares sense."""
    best = (np.inf, float(half.max()), 1.0)
    for n in np.linspace(0.2, 3.0, 57):
        profile = np.clip(1.0 - np.abs(s) ** (2.0 / n), 0.0, 1.0) ** (n / 2.0)
        a_x = float(profile @ half) / max(float(profile @ profile), 1e-12)
        err = float(np.sum((a_x * profile - half) ** 2))
        if err < best[0]:
            best = (err, a_x, float(n))
    return best[1], best[2]


def _with_depth(region: Supertoroid, points: np.ndarray) -> Supertoroid:
    """Width a_x, depth a_z and the exponents e and n from outlines drawn in 3D (a tracker), which
    wander around the crown: neither at its widest nor at its deepest.

    Every outline point, relative to the axis, lies on the surface when
    (x / a_x)^(2/e) + (z / a_z)^(2/e) = c^(2/e), with c = (1 - |s|^(2/n))^(n/2) the profile at its
    height. For fixed e and n that is linear in a_x^(-2/e) and a_z^(-2/e): a 2 x 2 least-squares
    solve for every (e, n) on a grid, and the pair whose surface passes closest to the points wins.
    Outlines drawn on a plane carry no depth: then a_z = FLAT_DEPTH * a_x and e = 1. The region and the
    points are in the region's own axes (x across the view it was drawn in).
    """
    y = points[:, 1] - region.alpha_y
    dx = np.abs(points[:, 0] - region.b_x - region.slope_x * y)
    dz = np.abs(points[:, 2] - region.b_z - region.slope_z * y)
    if dz.max(initial=0.0) < 0.1 * region.a_x:
        return replace(region, a_z=FLAT_DEPTH * region.a_x, e=1.0)
    s = np.abs(np.clip(y / region.a_y, -1.0, 1.0))
    ns = np.linspace(0.2, 3.0, 57)[:, None]
    profiles = np.clip(1.0 - s[None] ** (2.0 / ns), 0.0, 1.0) ** (ns / 2.0)  # (n, points)
    keep = profiles.min(axis=0) > 0.05
    dx, dz, profiles = dx[keep], dz[keep], profiles[:, keep]
    best = (np.inf, region)
    for e in np.linspace(0.2, 2.5, 47):
        x, z, c = dx ** (2.0 / e), dz ** (2.0 / e), profiles ** (2.0 / e)
        normal = np.array([[x @ x, x @ z], [x @ z, z @ z]])
        if abs(np.linalg.det(normal)) < 1e-12 * (x @ x) * (z @ z):
            continue
        coef = np.linalg.solve(normal, np.stack([c @ x, c @ z]))  # (2, n): a_x^(-2/e), a_z^(-2/e)
        valid = (coef > 0).all(axis=0)
        radius = np.maximum(coef[0][:, None] * x + coef[1][:, None] * z, 0.0) ** (e / 2.0)
        err = np.where(valid, ((radius - profiles) ** 2).sum(axis=1), np.inf)
        k = int(np.argmin(err))
        if err[k] < best[0]:
            a_x, a_z = coef[:, k] ** (-e / 2.0)
            best = (float(err[k]), replace(region, a_x=float(a_x), a_z=float(a_z), e=float(e), n=float(ns[k, 0])))
    return best[1]


def moved_region(region: Sphere | Supertoroid, by) -> Sphere | Supertoroid:
    """The region moved by the vector ``by``."""
    dx, dy, dz = (float(v) for v in by)
    if isinstance(region, Sphere):
        x, y, z = region.center
        return Sphere((x + dx, y + dy, z + dz), region.radius)
    return replace(region, b_x=region.b_x + dx, alpha_y=region.alpha_y + dy, b_z=region.b_z + dz)


def scaled_region(region: Sphere | Supertoroid, factor: float) -> Sphere | Supertoroid:
    """The region grown (factor > 1) or shrunk about its centre."""
    if isinstance(region, Sphere):
        return Sphere(region.center, region.radius * factor)
    return replace(region, a_x=region.a_x * factor, a_y=region.a_y * factor, a_z=region.a_z * factor)


def prune(ls: LString, module: int) -> LString:
    """Remove module ``module`` and everything that grows from it (the rest of its branch)."""
    end = int(brackets.branch_ends(ls.sym, np.array([module]))[0])
    keep = np.ones(len(ls), bool)
    keep[module:end] = False
    return ls.select(keep)


def seed_in_region(ls: LString, axiom: str, point) -> LString:
    """When no module lies in a region: start a new axis there, growing up (Onishi et al. 2003, 4.2).

    The new axis is a bracket at the start of the string (where the turtle is at the base): a move to
    ``point`` without drawing, a turn back to vertical, then ``axiom``.
    """
    from arbor.engine.modeling.modeler import ModelerSettings, path_modules

    point = np.asarray(point, float)
    path = np.stack([np.zeros(3), point, point + np.array([0.0, 1e-6, 0.0])])
    move, _ = path_modules(path, INITIAL_FRAME.copy(), np.ones(2), [], ModelerSettings(), "f")
    return concat(parse_lstring("[" + move + axiom + "]"), ls)
