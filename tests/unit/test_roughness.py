"""Rough-contact outputs (viscontact.problem.roughness).

Patch counts are checked on drawn patterns whose answer is known by construction (a patch cut by
each edge, one cut by a corner, diagonal neighbours) and against an independent algorithm: a plain
breadth-first flood fill with modular neighbours on random maps.
"""
from __future__ import annotations

from collections import deque

import numpy as np
import pytest

from viscontact.problem.roughness import contact_patches, roughness_metrics


def _flood_fill_count(contact: np.ndarray, periodic: bool) -> int:
    ny, nx = contact.shape
    seen = np.zeros_like(contact, dtype=bool)
    count = 0
    for start in zip(*np.nonzero(contact)):
        if seen[start]:
            continue
        count += 1
        seen[start] = True
        queue = deque([start])
        while queue:
            j, i = queue.popleft()
            for dj, di in ((1, 0), (-1, 0), (0, 1), (0, -1)):
                a, b = j + dj, i + di
                if periodic:
                    a, b = a % ny, b % nx
                elif not (0 <= a < ny and 0 <= b < nx):
                    continue
                if contact[a, b] and not seen[a, b]:
                    seen[a, b] = True
                    queue.append((a, b))
    return count


def test_drawn_patterns():
    c = np.zeros((8, 8), dtype=bool)
    c[3, 0:2] = c[3, 6:8] = True           # one patch cut by the x edges
    c[0, 4] = c[7, 4] = True               # one cut by the y edges
    assert contact_patches(c, periodic=False)[1] == 4
    assert contact_patches(c, periodic=True)[1] == 2
    corner = np.zeros((6, 6), dtype=bool)
    corner[0, 0] = corner[0, 5] = corner[5, 0] = corner[5, 5] = True  # the four corners: one patch
    assert contact_patches(corner, periodic=True)[1] == 1
    assert contact_patches(corner, periodic=False)[1] == 4
    diagonal = np.eye(5, dtype=bool)       # diagonal neighbours do not connect
    assert contact_patches(diagonal, periodic=True)[1] == 5
    assert contact_patches(np.zeros((4, 4), dtype=bool), periodic=True)[1] == 0
    assert contact_patches(np.ones((4, 4), dtype=bool), periodic=True)[1] == 1


@pytest.mark.parametrize("periodic", [False, True])
def test_against_flood_fill(periodic):
    rng = np.random.default_rng(11)
    for density in (0.2, 0.45, 0.6):
        for _ in range(20):
            c = rng.random((9, 12)) < density
            labels, count = contact_patches(c, periodic)
            assert count == _flood_fill_count(c, periodic)
            assert set(np.unique(labels[c])) == set(range(1, count + 1))
            assert np.all(labels[~c] == 0)


def test_metrics():
    p = np.zeros((4, 4))
    p[1, 1], p[1, 2], p[3, 3] = 2.0, 4.0, 6.0
    gap = np.where(p > 0, 0.0, 1.5e-6)
    m = roughness_metrics(p, gap, periodic=False)
    assert m.contact_fraction == 3 / 16
    assert m.contact_patches == 2
    assert m.mean_gap == pytest.approx(13 / 16 * 1.5e-6)
    assert m.mean_contact_pressure == pytest.approx(4.0)
    none = roughness_metrics(np.zeros((4, 4)), np.ones((4, 4)), periodic=True)
    assert (none.contact_fraction, none.contact_patches, none.mean_contact_pressure) == (0.0, 0, 0.0)
