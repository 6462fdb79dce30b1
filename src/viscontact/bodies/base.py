"""What every kind of body provides: the :class:`Body` protocol.

The *body* is the whole compliant solid under the rigid indenter: its material and its geometry (a
half-space, a layer on a *base*). Each kind lives in its own module and is a frozen dataclass
satisfying :class:`Body`:

* :class:`~viscontact.bodies.half_space.HomogeneousHalfSpace`: a half-space with a constant Poisson
  ratio (:mod:`viscontact.bodies.half_space`);
* :class:`~viscontact.bodies.bulk_elastic.BulkElasticHalfSpace`: a half-space whose bulk modulus K
  is elastic, so that nu(t) rises as G(t) relaxes (:mod:`viscontact.bodies.bulk_elastic`);
* :class:`~viscontact.bodies.layer.LayerOnBase`: a viscoelastic layer on a rigid or elastic base
  (:mod:`viscontact.bodies.layer`).

:func:`viscontact.bodies.registry.body_of` is the one place that maps a case's description of the
body (its ``material`` and the keys ``material.bulk_modulus`` or ``[layer]``) to one of them; every
other module asks the body (``problem.body``) instead of testing which kind it is. A new kind of
body is one module with such a class and one entry in :data:`viscontact.bodies.registry.BODIES`
(and the case schema's key that describes it).
"""
from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any, Protocol, runtime_checkable

from viscontact.bodies.compliance import ComplianceTerm, Compliance, ordered_components, term_substrate
from viscontact.numerics.arrays import ArrayBackend
from viscontact.numerics.exponentials import CreepSpectrum
from viscontact.numerics.grid import Grid
from viscontact.numerics.schemes import TimeScheme
from viscontact.physics.materials import Material

#: the case keys that describe a body besides its material, in the order the checkpoint
#: fingerprint has always hashed them (:func:`described_fingerprint`)
DESCRIPTION_KEYS = ("bulk_modulus", "layer")


@runtime_checkable
class Body(Protocol):
    """A compliant body: everything the solvers, results, checkpoints, guards and estimates need.

    Attributes
    ----------
    material
        The viscoelastic material (its shear relaxation; for a layer, the layer's).
    description
        The case keys (of :data:`DESCRIPTION_KEYS` or a new body's own) that describe the body
        besides ``material``, with their values: empty for the homogeneous half-space.
    subsurface_stresses
        Whether the subsurface stresses of :mod:`viscontact.physics.subsurface` (the elastic fields
        of a homogeneous half-space with constant nu) are valid for it.
    contact_model
        Names the closed form of :meth:`contact_radius` (in the guards' messages).
    """

    material: Material

    @property
    def description(self) -> Mapping[str, Any]: ...

    @property
    def subsurface_stresses(self) -> bool: ...

    @property
    def contact_model(self) -> str: ...

    def compliance(self, grid: Grid, components: Sequence[str], scheme: str | TimeScheme, dt: float, *,
                   workers: int = -1, direct: bool = False, fft: str = "scipy",
                   backend: ArrayBackend | None = None) -> Compliance:
        """The surface compliance on ``grid`` (the kernels ``components`` among ``zz``, ``zx``, ``xz``,
        ``xx``; ``zz`` always) with the hereditary integral of ``scheme`` and step ``dt`` [s]: what
        the contact solvers use. ``workers``: FFT threads; ``direct``: the literal hereditary sum;
        ``fft``: the DC-FFT transforms by backend name; ``backend``: where the fields live."""
        ...

    def stability_responses(self) -> list[CreepSpectrum]:
        """Time responses [1/Pa] whose step stability bounds dt
        (:func:`~viscontact.numerics.schemes.stable_step_limit`)."""
        ...

    def size(self) -> tuple[int, int]:
        """(history fields per traction component, kernels per kernel component) of
        :meth:`compliance`, for the memory estimate."""
        ...

    def result_attributes(self) -> dict[str, Any]:
        """Global attributes a result of this body carries beside the material's."""
        ...

    def fingerprint(self) -> bytes:
        """What the body adds to a checkpoint's problem fingerprint (empty for the half-space)."""
        ...

    def material_summary(self) -> str:
        """How ``viscontact material`` names the body's Poisson ratio (one phrase)."""
        ...

    def contact_radius(self, load: float, shape: ContactShape, compliance_factor: float = 1.0) -> float:
        """Estimated contact size [m] (:meth:`ContactShape.size_at_load`: a radius, a roller's
        half-width) of the rigid ``shape`` pressed with ``load`` [N] when the material's compliance is
        ``compliance_factor`` times its instantaneous value (creep: the Lee & Radok ratio
        int J dW / (J(0) W) >= 1; inf: a fluid's unbounded creep, an infinite contact)."""
        ...

    def contact_radius_at_approach(self, approach: float, shape: ContactShape) -> float:
        """Estimated contact size [m] of the rigid ``shape`` pressed to the approach ``approach`` [m]."""
        ...


@runtime_checkable
class ContactShape(Protocol):
    """What a body's contact estimate asks of an indenter's shape (the shapes of
    :mod:`viscontact.problem.shapes`): its elastic contact on a half-space of contact modulus E* [Pa].

    Attributes
    ----------
    grows
        Whether the contact grows with the load (False: a flat punch's face, its size at any load).
    """

    grows: bool

    def load_at_size(self, size: float, contact_modulus: float) -> float:
        """The load [N] whose contact has the size ``size`` [m] on a half-space of E* [Pa]."""
        ...

    def size_at_load(self, load: float, contact_modulus: float) -> float:
        """The contact size [m] under ``load`` [N] on a half-space of E* [Pa]."""
        ...

    def size_at_approach(self, approach: float) -> float:
        """The contact size [m] at the approach ``approach`` [m] on a half-space."""
        ...


def half_space_contact_radius(load: float, shape: ContactShape, contact_modulus: float,
                              compliance_factor: float = 1.0) -> float:
    """The contact size [m] of ``shape`` under ``load`` [N] on a half-space of instantaneous contact
    modulus E* [Pa] whose compliance is ``compliance_factor`` times its instantaneous one (creep, Lee &
    Radok 1960: the elastic relation with E*/c): ``shape.size_at_load(load, E*/c)``; inf for an
    unbounded creep (c = inf) of a growing contact, NaN for no estimate (c NaN)."""
    if not math.isfinite(compliance_factor):
        if not shape.grows and compliance_factor > 0:
            return shape.size_at_load(load, contact_modulus)
        return math.inf if compliance_factor > 0 else math.nan
    return shape.size_at_load(load, contact_modulus / compliance_factor)


def described_fingerprint(description: Mapping[str, Any]) -> bytes:
    """The fingerprint part of a body described by ``description`` (:attr:`Body.description`):
    nothing for an empty description (the half-space's fingerprint stays what it was before bodies
    had one), else ``repr`` of {"bulk_modulus": ..., "layer": ...} with the described values in
    place of None (the bytes hashed since the first layered checkpoints, so they still resume), a new
    body's own keys after them."""
    if not description:
        return b""
    full = {key: None for key in DESCRIPTION_KEYS}
    full.update(description)
    return repr(full).encode()


class TermBody:
    """What a body of :class:`~viscontact.bodies.compliance.ComplianceTerm` s shares (a base class of
    the bodies whose compliance is :func:`~viscontact.bodies.compliance.term_substrate` of their
    :meth:`terms`; the half-space with constant nu builds its own): :meth:`compliance` and the
    :meth:`fingerprint` of its :attr:`~Body.description`."""

    description: Mapping[str, Any]

    def terms(self, grid: Grid, components: tuple[str, ...]) -> list[ComplianceTerm]:
        """The compliance terms of the kernels ``components`` (ordered, ``zz`` first) on ``grid``."""
        raise NotImplementedError

    def compliance(self, grid: Grid, components: Sequence[str], scheme: str | TimeScheme, dt: float, *,
                   workers: int = -1, direct: bool = False, fft: str = "scipy",
                   backend: ArrayBackend | None = None) -> Compliance:
        """:meth:`terms` as a :class:`~viscontact.bodies.compliance.Compliance` (:meth:`Body.compliance`)."""
        terms = self.terms(grid, ordered_components(components))
        return term_substrate(grid, terms, scheme, dt, workers=workers, direct=direct, backend=backend, fft=fft)

    def fingerprint(self) -> bytes:
        """:func:`described_fingerprint` of the description."""
        return described_fingerprint(self.description)
