"""Adhesion between the indenter and the body: the traction-separation law of the surface
(``[adhesion]`` of a case file, SPEC §7).

Absent (``Problem.adhesion is None``) the surface obeys the seed's Kuhn-Tucker conditions (p >= 0,
gap >= 0, complementarity). With :class:`AdhesionSettings` a tension acts across an open gap: for
``law = "maugis_dugdale"`` (Maugis 1992, J. Colloid Interface Sci. 150, 243) a constant tension
``cohesive_stress`` sigma_0 [Pa] wherever 0 < gap < h_0 = w / sigma_0, nothing beyond, the Dupre
work of adhesion w = sigma_0 h_0 [J/m^2]. Solved by :mod:`viscontact.numerics.adhesive`. For
``law = "exponential"`` (the exponential interaction of Muser 2014, Beilstein J. Nanotechnol. 5, 419) a
tension sigma(g) = (w / rho) exp(-g / rho) across every open gap g, of peak w / rho and work of
separation w, with the ``range`` rho [m]. Solved by :mod:`viscontact.numerics.adhesive_exponential`.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from viscontact.errors import ParameterError

#: the traction-separation laws of the surface, by name
ADHESION_LAWS = ("maugis_dugdale", "exponential")


@dataclass(frozen=True)
class AdhesionSettings:
    """The adhesive law of the surface.

    Attributes
    ----------
    work_of_adhesion
        Dupre work of adhesion w [J/m^2], > 0.
    cohesive_stress
        sigma_0 [Pa], > 0: the tension of the Maugis-Dugdale law across an open gap below its range
        (None with the exponential law).
    law
        ``"maugis_dugdale"`` or ``"exponential"``.
    decay_length
        rho [m], > 0: the range of the exponential law (None with the Maugis-Dugdale law).
    """

    work_of_adhesion: float
    cohesive_stress: float | None
    law: str = "maugis_dugdale"
    decay_length: float | None = None

    def __post_init__(self) -> None:
        """Raises :class:`~viscontact.errors.ParameterError` naming the ``adhesion.`` key: w, sigma_0 or rho
        (``range``) not a finite number > 0, an unknown law, the other law's parameter given."""
        if self.law not in ADHESION_LAWS:
            raise ParameterError("adhesion.law",
                                 f"must be one of {', '.join(map(repr, ADHESION_LAWS))}, got {self.law!r}")
        own = ("cohesive_stress", " Pa", "cohesive_stress") if self.law == "maugis_dugdale" else \
            ("decay_length", " m", "range")
        other = ("decay_length", "range") if self.law == "maugis_dugdale" else ("cohesive_stress", "cohesive_stress")
        if getattr(self, other[0]) is not None:
            raise ParameterError(f"adhesion.{other[1]}", f"not a key of adhesion.law = {self.law!r}")
        for attribute, unit, key in (("work_of_adhesion", " J/m^2", "work_of_adhesion"), own):
            value = getattr(self, attribute)
            if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
                    or not np.isfinite(value) or not value > 0:
                raise ParameterError(f"adhesion.{key}", f"must be a finite number > 0{unit}, got {value!r}")

    @property
    def range(self) -> float:
        """The law's range [m]: h_0 = w / sigma_0, the gap beyond which no Maugis-Dugdale tension acts;
        rho, over which the exponential tension falls by e."""
        if self.law == "exponential":
            return float(self.decay_length)
        return float(self.work_of_adhesion) / float(self.cohesive_stress)

    @property
    def peak_stress(self) -> float:
        """The law's largest tension [Pa]: sigma_0, or w / rho of the exponential law (the Maugis-Dugdale
        law of the same peak has the range h_0 = rho: the equivalence of equal peak stresses, Johnson &
        Greenwood 1997, J. Colloid Interface Sci. 192, 326, for the Lennard-Jones law)."""
        if self.law == "exponential":
            return float(self.work_of_adhesion) / float(self.decay_length)
        return float(self.cohesive_stress)
