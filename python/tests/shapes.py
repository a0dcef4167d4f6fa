"""Generated test shapes: points sampled on surfaces with parts, reproducibly."""
import numpy as np


def _sphere(rng, n, centre, radius):
    v = rng.normal(size=(n, 3))
    v /= np.linalg.norm(v, axis=1)[:, None]
    return np.asarray(centre) + radius * v


def _cylinder(rng, n, start, axis, length, radius):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    a = np.cross(axis, [0.0, 0.0, 1.0] if abs(axis[2]) < 0.9 else [1.0, 0.0, 0.0])
    a /= np.linalg.norm(a)
    b = np.cross(axis, a)
    t = rng.uniform(0.0, length, n)
    phi = rng.uniform(0.0, 2 * np.pi, n)
    return (np.asarray(start) + t[:, None] * axis +
            radius * (np.cos(phi)[:, None] * a + np.sin(phi)[:, None] * b))


def limbs(n=3000, seed=1):
    """A ball (radius 1) with four limbs (radius 0.3, length 1.6) along +-x and +-y: float64
    points, uniform by area, shuffled."""
    rng = np.random.default_rng(seed)
    ball_area = 4 * np.pi
    limb_area = 2 * np.pi * 0.3 * 1.6
    total = ball_area + 4 * limb_area
    n_limb = int(n * limb_area / total)
    parts = [_sphere(rng, n - 4 * n_limb, (0, 0, 0), 1.0)]
    for axis in ((1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0)):
        start = 0.95 * np.asarray(axis, float)
        parts.append(_cylinder(rng, n_limb, start, axis, 1.6, 0.3))
    points = np.concatenate(parts)
    inside = np.linalg.norm(points, axis=1) < 0.999  # limb points inside the ball
    points[inside] = _sphere(rng, int(inside.sum()), (0, 0, 0), 1.0)
    return points[rng.permutation(len(points))]


def with_nan_rows(points, every=37):
    """A copy with every `every`-th row NaN (one row with a single NaN coordinate, one with
    inf); returns (points, mask of the non-finite rows)."""
    out = np.array(points, copy=True)
    bad = np.zeros(len(out), bool)
    bad[::every] = True
    out[bad] = np.nan
    rows = np.flatnonzero(bad)
    out[rows[1]] = (0.5, np.nan, 0.5)
    out[rows[2]] = (np.inf, 0.0, 0.0)
    return out, bad
