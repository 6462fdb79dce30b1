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
Each law is one :class:`AdhesionLaw` registered by name in :data:`ADHESION_LAWS`
(:class:`MaugisDugdale`, :class:`Exponential`); its solver is registered under the same name in
:mod:`viscontact.solvers.adhesive_law`.
"""
from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from viscontact.errors import ParameterError


class AdhesionLaw(ABC):
    """A traction-separation law of the surface: the tension sigma(g) [Pa] across an open gap g [m],
    given by the Dupre work of adhesion w [J/m^2] and one parameter of its own. A new law is one
    subclass here, registered by name with :func:`register_adhesion_law` (its case key in
    ``io/case.py``'s ``AdhesionSection``), and its solver in ``solvers/adhesive_law.py``.

    Attributes
    ----------
    name
        The law's name, the value of ``adhesion.law``.
    key
        The ``adhesion.`` case key of its parameter.
    attribute
        The attribute of :class:`AdhesionSettings` holding that parameter.
    unit
        The parameter's SI unit.
    label
        The law's name in a message.
    reaches_every_cell
        Whether its tension acts across every open gap (no cut-off): the tension at the domain's edge
        is then its tail, and the domain-edge check judges the compressed contact only.
    steady
        Whether the steady sliding solver supports it.
    """

    name: ClassVar[str]
    key: ClassVar[str]
    attribute: ClassVar[str]
    unit: ClassVar[str]
    label: ClassVar[str]
    reaches_every_cell: ClassVar[bool]
    steady: ClassVar[bool]

    @abstractmethod
    def range(self, settings: AdhesionSettings) -> float:
        """The law's range [m] (:attr:`AdhesionSettings.range`)."""

    @abstractmethod
    def peak_stress(self, settings: AdhesionSettings) -> float:
        """The law's largest tension [Pa] (:attr:`AdhesionSettings.peak_stress`)."""

    @abstractmethod
    def tail(self, settings: AdhesionSettings, gap: float) -> float:
        """The tension at the gap ``gap`` [m] as a fraction of its peak, sigma(g) / max sigma."""

    @abstractmethod
    def tail_gap(self, settings: AdhesionSettings, fraction: float) -> float:
        """The least gap [m] beyond which the tension is below ``fraction`` of its peak."""


#: the traction-separation laws of the surface, by name (:func:`register_adhesion_law`)
ADHESION_LAWS: dict[str, AdhesionLaw] = {}


def register_adhesion_law(cls: type[AdhesionLaw]) -> type[AdhesionLaw]:
    """Register the law ``cls`` under its name in :data:`ADHESION_LAWS` (a class decorator)."""
    ADHESION_LAWS[cls.name] = cls()
    return cls


@register_adhesion_law
class MaugisDugdale(AdhesionLaw):
    """The Maugis-Dugdale law (Maugis 1992, J. Colloid Interface Sci. 150, 243): a constant tension
    sigma(g) = sigma_0 [Pa] (``cohesive_stress``) wherever 0 < g < h_0 = w / sigma_0, none beyond, so
    that w = sigma_0 h_0 [J/m^2]. Its cut-off at h_0 leaves no tail at the domain's edge (the solved
    tension there is judged as the contact is)."""

    name = "maugis_dugdale"
    key = "cohesive_stress"
    attribute = "cohesive_stress"
    unit = "Pa"
    label = "Maugis-Dugdale"
    reaches_every_cell = False
    steady = True

    def range(self, settings: AdhesionSettings) -> float:
        """h_0 = w / sigma_0 [m], the gap beyond which no tension acts."""
        return float(settings.work_of_adhesion) / float(settings.cohesive_stress)

    def peak_stress(self, settings: AdhesionSettings) -> float:
        """sigma_0 [Pa]."""
        return float(settings.cohesive_stress)

    def tail(self, settings: AdhesionSettings, gap: float) -> float:
        """1 below h_0, 0 from h_0 on."""
        return 1.0 if gap < self.range(settings) else 0.0

    def tail_gap(self, settings: AdhesionSettings, fraction: float) -> float:
        """h_0 [m], for any fraction < 1."""
        return self.range(settings)


@register_adhesion_law
class Exponential(AdhesionLaw):
    """The exponential law (the exponential interaction of Muser 2014, Beilstein J. Nanotechnol. 5,
    419): a tension sigma(g) = (w / rho) exp(-g / rho) [Pa] across every open gap g, of peak w / rho
    and work of separation w [J/m^2], with the ``range`` rho [m]. Solved by
    :mod:`viscontact.numerics.adhesive_exponential`."""

    name = "exponential"
    key = "range"
    attribute = "decay_length"
    unit = "m"
    label = "exponential"
    reaches_every_cell = True
    steady = False

    def range(self, settings: AdhesionSettings) -> float:
        """rho [m], over which the tension falls by e."""
        return float(settings.decay_length)

    def peak_stress(self, settings: AdhesionSettings) -> float:
        """w / rho [Pa] (the Maugis-Dugdale law of the same peak has the range h_0 = rho: the
        equivalence of equal peak stresses, Johnson & Greenwood 1997, J. Colloid Interface Sci. 192,
        326, for the Lennard-Jones law)."""
        return float(settings.work_of_adhesion) / float(settings.decay_length)

    def tail(self, settings: AdhesionSettings, gap: float) -> float:
        """exp(-g / rho)."""
        return math.exp(-gap / self.range(settings))

    def tail_gap(self, settings: AdhesionSettings, fraction: float) -> float:
        """rho ln(1 / fraction) [m]."""
        return -math.log(fraction) * self.range(settings)


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
        The name of a registered law (:data:`ADHESION_LAWS`): ``"maugis_dugdale"`` or ``"exponential"``.
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
        kind = ADHESION_LAWS.get(self.law)
        if kind is None:
            raise ParameterError("adhesion.law",
                                 f"must be one of {', '.join(map(repr, ADHESION_LAWS))}, got {self.law!r}")
        for other in ADHESION_LAWS.values():
            if other is not kind and getattr(self, other.attribute) is not None:
                raise ParameterError(f"adhesion.{other.key}", f"not a key of adhesion.law = {self.law!r}")
        own = (kind.attribute, f" {kind.unit}", kind.key)
        for attribute, unit, key in (("work_of_adhesion", " J/m^2", "work_of_adhesion"), own):
            value = getattr(self, attribute)
            if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
                    or not np.isfinite(value) or not value > 0:
                raise ParameterError(f"adhesion.{key}", f"must be a finite number > 0{unit}, got {value!r}")

    @property
    def kind(self) -> AdhesionLaw:
        """The registered law of :attr:`law` (:data:`ADHESION_LAWS`)."""
        return ADHESION_LAWS[self.law]

    @property
    def range(self) -> float:
        """The law's range [m]: h_0 = w / sigma_0, the gap beyond which no Maugis-Dugdale tension acts;
        rho, over which the exponential tension falls by e."""
        return self.kind.range(self)

    @property
    def peak_stress(self) -> float:
        """The law's largest tension [Pa]: sigma_0, or w / rho of the exponential law."""
        return self.kind.peak_stress(self)
