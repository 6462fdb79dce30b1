"""Rough-contact outputs: real contact area, contact patches, mean gap, mean contact pressure.

Contact patches are the 4-connected components of the contact set (points with p > 0), counted by
``scipy.ndimage.label``; on a periodic domain a patch that leaves the period at one edge and re-enters
at the opposite one is one patch: labels that touch across opposite edges are merged (union-find).
Diagonal neighbours do not connect (the usual convention of rough-contact studies, e.g. Hyun,
Pei, Molinari & Robbins, Phys. Rev. E 70, 026117 (2004)).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from viscontact.numerics.grid import mask_span


def contact_patches(contact: np.ndarray, periodic: bool = False) -> tuple[np.ndarray, int]:
    """Label the 4-connected patches of a boolean contact map (n, m).

    Returns (labels, count): labels 1..count on contact points, 0 elsewhere. With ``periodic``
    the first and last rows (and columns) are neighbours.
    """
    from scipy import ndimage  # imported where used: scipy.ndimage weighs several MiB

    labels, count = ndimage.label(contact)
    if not periodic or count == 0:
        return labels, count
    parent = np.arange(count + 1)

    def root(a: int) -> int:
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for first, last in ((labels[0, :], labels[-1, :]), (labels[:, 0], labels[:, -1])):
        touching = (first > 0) & (last > 0)
        for a, b in zip(first[touching], last[touching]):
            ra, rb = root(int(a)), root(int(b))
            if ra != rb:
                parent[max(ra, rb)] = min(ra, rb)
    roots = np.array([root(a) for a in range(count + 1)])
    unique, relabel = np.unique(roots, return_inverse=True)  # root 0 (background) stays 0
    return relabel[labels], int(unique.size - 1)


@dataclass(frozen=True)
class RoughContactMetrics:
    """Summary of a rough contact (field names as in :class:`~viscontact.problem.records.StepRecord`).

    Attributes
    ----------
    contact_fraction
        Real contact area / nominal area [-].
    contact_patches
        Number of contact patches.
    mean_gap
        Mean of the deformed gap over the domain [m] (the mean separation).
    mean_contact_pressure
        Load / real contact area [Pa] (0 without contact).
    """

    contact_fraction: float
    contact_patches: int
    mean_gap: float
    mean_contact_pressure: float


def roughness_metrics(pressure: np.ndarray, gap: np.ndarray, periodic: bool = False) -> RoughContactMetrics:
    """Metrics of a contact solution: ``pressure`` p [Pa] and deformed ``gap`` g [m] on the grid
    (same shape). Contact is p > 0."""
    contact = pressure > 0
    n_contact = int(contact.sum())
    if not periodic and n_contact:  # label the contact's bounding box only: the same patches
        rows, cols = mask_span(contact, 0), mask_span(contact, 1)
        _, patches = contact_patches(contact[rows[0]:rows[1], cols[0]:cols[1]])
    else:
        _, patches = contact_patches(contact, periodic)
    mean_p = float(pressure[contact].mean()) if n_contact else 0.0
    return RoughContactMetrics(n_contact / contact.size, patches, float(gap.mean()), mean_p)
