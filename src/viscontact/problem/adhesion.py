"""Adhesion between the indenter and the body: the traction-separation law of the surface
(``[adhesion]`` of a case file, SPEC §7).

Absent (``Problem.adhesion is None``) the surface obeys the seed's Kuhn-Tucker conditions (p >= 0,
gap >= 0, complementarity). With :class:`AdhesionSettings` a tension acts across an open gap: for
``law = "maugis_dugdale"`` (Maugis 1992, J. Colloid Interface Sci. 150, 243) a constant tension
``cohesive_stress`` sigma_0 [Pa] wherever 0 < gap < h_0 = w / sigma_0, nothing beyond, the Dupre
work of adhesion w = sigma_0 h_0 [J/m^2]. Solved by :mod:`viscontact.numerics.adhesive`.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from viscontact.errors import ParameterError

#: the traction-separation laws of the surface, by name
ADHESION_LAWS = ("maugis_dugdale",)


@dataclass(frozen=True)
class AdhesionSettings:
    """The adhesive law of the surface.

    Attributes
    ----------
    work_of_adhesion
        Dupre work of adhesion w [J/m^2], > 0.
    cohesive_stress
        sigma_0 [Pa], > 0: the tension of the Maugis-Dugdale law across an open gap below its range.
    law
        ``"maugis_dugdale"`` (the only one so far).
    """

    work_of_adhesion: float
    cohesive_stress: float
    law: str = "maugis_dugdale"

    def __post_init__(self) -> None:
        """Raises :class:`~viscontact.errors.ParameterError` naming the ``adhesion.`` key: w or sigma_0 not
        a finite number > 0, an unknown law."""
        if self.law not in ADHESION_LAWS:
            raise ParameterError("adhesion.law",
                                 f"must be one of {', '.join(map(repr, ADHESION_LAWS))}, got {self.law!r}")
        for key, unit in (("work_of_adhesion", " J/m^2"), ("cohesive_stress", " Pa")):
            value = getattr(self, key)
            if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
                    or not np.isfinite(value) or not value > 0:
                raise ParameterError(f"adhesion.{key}", f"must be a finite number > 0{unit}, got {value!r}")

    @property
    def range(self) -> float:
        """h_0 = w / sigma_0 [m]: the gap beyond which no tension acts."""
        return float(self.work_of_adhesion) / float(self.cohesive_stress)
