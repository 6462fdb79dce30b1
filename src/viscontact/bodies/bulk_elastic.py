"""Time-dependent Poisson ratio: shear relaxing as a Prony series, bulk modulus elastic.

A polymer's bulk modulus K hardly relaxes while its shear modulus does, so the Poisson ratio rises
with time. By the correspondence principle the elastic surface influence factors become operators
whose Carson transforms (s times the Laplace transform) are the elastic factors evaluated at
G~(s) = s G^(s) and

    nu~(s) = (3K - 2 G~) / (2 (3K + G~))                                          (Carson domain)

(e.g. Tschoegl, *The Phenomenological Theory of Linear Viscoelastic Behavior*, 1989, ch. 2;
Lakes, *Viscoelastic Materials*, 2009, sec. 2.7). Every factor of the half-space kernels
(Johnson, *Contact Mechanics*, Eqs. 3.19-3.20, 3.86-3.87; see :mod:`viscontact.physics.kernels`) splits
into two partial fractions in G~:

    (1 - nu)/G    = 1/(2 G~) + 3 / (2 (G~ + 3K))       normal  (u_z of p)
    1/G           = 1/G~                               tangential, shape 1/r
    nu/G          = 1/(2 G~) - 3 / (2 (G~ + 3K))       tangential, shape (x^2/r^3 - 1/r)
    (1 - 2 nu)/G  = 3 / (G~ + 3K)                      coupling (u_x of p, u_z of q_x)

so only two creep functions are needed: the shear creep compliance J(t) (Carson 1/G~) and the
creep function L(t) of the modulus G(t) + 3K (Carson 1/(G~ + 3K)). Both are exact sums of
exponentials, J0 + sum_m J_m (1 - exp(-t/lambda_m)), with retardation rates 1/lambda_m the roots
of G~(s) = -c (c = 0 for J, 3K for L). With G~(s) = G(0) - sum_i g_i r_i / (s + r_i) (r_i = 1/tau_i)
this is a secular equation: G~ is increasing between its poles -r_i, so exactly one root lies in
each interval (-r_{i+1}, -r_i) and one in (-r_1, 0). Each root is found by bisection on the
equation written relative to the nearer pole (as LAPACK's dlaed4 does), so the
rates keep full relative accuracy for spectra over many decades, where the roots of the expanded
polynomial (coefficients spanning hundreds of orders of magnitude) do not. The amplitude of a root
s_m = -rho_m is the residue: J_m = 1 / (rho_m G~'(s_m)), G~'(s) = sum_i g_i r_i / (s + r_i)^2.

With the shape kernels at unit modulus taken at nu = 0 (``S``) and their nu-derivative (``D``),
the half-space displacements are

    u_z = S_zz [(1-nu)/G] p + S_zx [(1-2nu)/G] q_x
    u_x = S_xx [1/G] q_x + D_xx [nu/G] q_x + S_xz [(1-2nu)/G] p

where the bracketed operators act as hereditary convolutions with the spectra above;
:func:`half_space_terms` regroups them by the two basis functions J and L (two histories per
traction component, each with one internal field per retardation time, :mod:`viscontact.numerics.history`).

:class:`BulkElasticHalfSpace` is the body (:class:`~viscontact.bodies.base.Body`) of the case key
``material.bulk_modulus``.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np

from viscontact.bodies.base import ContactShape, TermBody, half_space_contact_radius
from viscontact.bodies.compliance import ComplianceTerm
from viscontact.errors import ParameterError
from viscontact.numerics.exponentials import CreepSpectrum, linear_combination
from viscontact.numerics.grid import Grid
from viscontact.physics.kernels import influence_coefficients
from viscontact.physics.materials import Material
from viscontact.physics.periodic import periodic_influence_coefficients
from viscontact.physics.prony import prony_creep_spectra, prony_creep_spectrum  # noqa: F401 (bodies.layer)
from viscontact.physics.reference import contact_modulus
from viscontact.physics.steady_kernels import SteadyKernelBuilder, SteadyShape

#: the factor names of :meth:`BulkElasticMaterial.factor`
FACTORS = ("normal", "tangential", "tangential_poisson", "coupling")


@dataclass(frozen=True)
class BulkElasticMaterial:
    """Isotropic viscoelastic material with a relaxing shear modulus and an elastic bulk modulus.

    Parameters
    ----------
    shear
        The shear relaxation modulus G(t) (its ``poisson_ratio`` is not used).
    bulk_modulus
        K [Pa], elastic; ``inf`` for an incompressible material. K >= 2 G(0)/3 so that
        nu(0) >= 0.

    Examples
    --------
    The seed's material with K = 10 G(0): nu rises from 0.45 to 0.495 as G relaxes, and the normal
    factor (1 - nu)/G gains the retardation time of G(t) + 3K beside that of J(t):

    >>> from viscontact.physics.materials import Material
    >>> m = BulkElasticMaterial(Material.zener(1.93e6, 1.93e5, 0.01, 0.3), 19.3e6)
    >>> round(m.poisson_ratio_instantaneous, 4), round(m.poisson_ratio_long_term, 4)
    (0.4516, 0.495)
    >>> m.factor("normal").retardation_times.round(5).tolist()
    [0.00103, 0.01]
    """

    shear: Material
    bulk_modulus: float

    def __post_init__(self) -> None:
        k, g0 = self.bulk_modulus, self.shear.shear_modulus_instantaneous
        if np.isnan(k) or not k >= 2.0 * g0 / 3.0:
            raise ParameterError("material.bulk_modulus",
                                 f"must be >= 2 G(0)/3 = {2 * g0 / 3:.6g} Pa (Poisson ratio nu(0) >= 0), got {k}")

    @staticmethod
    def poisson_ratio_of(shear_modulus: float, bulk_modulus: float) -> float:
        """nu = (3K - 2G) / (2 (3K + G)) [-] (0.5 for K = inf)."""
        if np.isinf(bulk_modulus):
            return 0.5
        return float((3 * bulk_modulus - 2 * shear_modulus) / (2 * (3 * bulk_modulus + shear_modulus)))

    @property
    def poisson_ratio_instantaneous(self) -> float:
        """nu(0) from G(0) and K [-]."""
        return self.poisson_ratio_of(self.shear.shear_modulus_instantaneous, self.bulk_modulus)

    @property
    def poisson_ratio_long_term(self) -> float:
        """nu(inf) from G(inf) and K [-]."""
        return self.poisson_ratio_of(self.shear.shear_modulus_long_term, self.bulk_modulus)

    @cached_property
    def shear_creep(self) -> CreepSpectrum:
        """J(t), Carson transform 1/G~(s) [1/Pa]."""
        m = self.shear
        return prony_creep_spectrum(m.g_inf, m.g, m.tau)

    @cached_property
    def bulk_shear_creep(self) -> CreepSpectrum:
        """L(t), Carson transform 1/(G~(s) + 3K) [1/Pa] (zero when K = inf)."""
        m = self.shear
        return prony_creep_spectrum(m.g_inf, m.g, m.tau, 3.0 * self.bulk_modulus)

    def factor(self, name: str) -> CreepSpectrum:
        """Time response [1/Pa] of an influence factor (module docstring): ``normal`` (1-nu)/G,
        ``tangential`` 1/G, ``tangential_poisson`` nu/G, ``coupling`` (1-2nu)/G."""
        j, l_ = self.shear_creep, self.bulk_shear_creep
        parts = {"normal": [(0.5, j), (1.5, l_)], "tangential": [(1.0, j)],
                 "tangential_poisson": [(0.5, j), (-1.5, l_)], "coupling": [(3.0, l_)]}
        if name not in parts:
            raise ValueError(f"factor must be one of {FACTORS}, got {name!r}")
        return linear_combination(parts[name])

    def elastic_factor(self, name: str, shear_modulus: float) -> float:
        """The same factor [1/Pa] of an elastic material (G, K), nu from :meth:`poisson_ratio_of`."""
        nu = self.poisson_ratio_of(shear_modulus, self.bulk_modulus)
        return {"normal": (1 - nu), "tangential": 1.0, "tangential_poisson": nu,
                "coupling": (1 - 2 * nu)}[name] / shear_modulus


def half_space_terms(grid: Grid, material: BulkElasticMaterial,
                     components: tuple[str, ...] = ("zz", "xx", "xz", "zx")) -> list[ComplianceTerm]:
    """Compliance terms of the homogeneous half-space with K elastic (module docstring), grouped by
    the two basis creep functions J ("shear") and L ("bulk") so that each traction component needs
    two hereditary histories (2M internal fields for an M-term Prony series, twice the
    constant-nu cost) and each displacement at most three kernels:

        u_z = S_zz/2 (J (*) dp) + 3 S_zz/2 (L (*) dp) + 3 S_zx (L (*) dq)
        u_x = (S_xx + D_xx/2) (J (*) dq) - 3 D_xx/2 (L (*) dq) + 3 S_xz (L (*) dp)

    The kernels of :mod:`viscontact.physics.kernels` are affine in nu, IC(nu) = IC(0) + nu (IC(1) - IC(0)):
    ``S = IC(0)`` and ``D = IC(1) - IC(0)`` are the shape parts (on a periodic grid those of
    :func:`~viscontact.physics.periodic.periodic_influence_coefficients`, affine in nu too). Each term's
    steady shape (:class:`~viscontact.physics.steady_kernels.SteadyShape`, DC-FFT grids) is the same
    combination of :class:`~viscontact.physics.steady_kernels.SteadyKernelBuilder` kernels at nu = 0 and 1,
    so steady sliding integrates each part with its own spectrum. Terms whose response vanishes
    (every L term when K = inf) are left out.
    """
    kernels_at = periodic_influence_coefficients if grid.periodic else influence_coefficients
    at0 = kernels_at(grid, 0.0)
    d_xx = kernels_at(grid, 1.0)["xx"] - at0["xx"] if "xx" in components else None
    shear, bulk = material.shear_creep, material.bulk_shear_creep
    # (kernel, response, steady shape: (nu of the half-space kernel, factor) pairs)
    parts = {
        "zz": [(0.5 * at0["zz"], shear, ((0.0, 0.5),)), (1.5 * at0["zz"], bulk, ((0.0, 1.5),))],
        "xx": [(at0["xx"] + 0.5 * d_xx, shear, ((0.0, 0.5), (1.0, 0.5))),
               (-1.5 * d_xx, bulk, ((0.0, 1.5), (1.0, -1.5)))] if d_xx is not None else [],
        "xz": [(3.0 * at0["xz"], bulk, ((0.0, 3.0),))],
        "zx": [(3.0 * at0["zx"], bulk, ((0.0, 3.0),))],
    }
    builders: dict[tuple[float, str], SteadyKernelBuilder] = {}

    def shape(comp: str, pieces: tuple[tuple[float, float], ...]) -> SteadyShape | None:
        if grid.periodic:
            return None
        for nu, _ in pieces:
            builders.setdefault((nu, comp), SteadyKernelBuilder(grid, nu, (comp,)))
        return SteadyShape(tuple((builders[(nu, comp)], comp, factor) for nu, factor in pieces))

    terms: list[ComplianceTerm] = []
    for comp in components:
        for kernel, response, pieces in parts[comp]:
            if response.instantaneous == 0.0 and not np.any(response.amplitudes):
                continue
            label = "shear" if response is shear else "bulk"
            terms.append(ComplianceTerm(comp[0], comp[1], kernel, response, f"{comp}:{label}", shape(comp, pieces)))
    return terms


@dataclass(frozen=True)
class BulkElasticHalfSpace(TermBody):
    """The homogeneous half-space of a material whose shear modulus relaxes while its bulk modulus K
    stays elastic, so that nu(t) rises from nu(0) to nu(inf) (module docstring): a
    :class:`~viscontact.bodies.base.Body` of the terms of :func:`half_space_terms` (two histories per
    traction component, J(t) and L(t)). Its fingerprint part: {"bulk_modulus": K, "layer": None}.

    Parameters
    ----------
    material
        The shear relaxation G(t) (its ``poisson_ratio``, nu(0) in a case, is not used by the compliance).
    bulk_modulus
        K [Pa] (the case key ``material.bulk_modulus``, kept as given: it enters the checkpoint
        fingerprint as such).
    """

    material: Material
    bulk_modulus: float

    subsurface_stresses = False
    contact_model = "with nu(0), Lee & Radok creep"

    @cached_property
    def elastic_bulk(self) -> BulkElasticMaterial:
        """G(t) with the elastic K (checks K >= 2 G(0)/3)."""
        return BulkElasticMaterial(self.material, self.bulk_modulus)

    @property
    def description(self) -> Mapping[str, Any]:
        return {"bulk_modulus": self.bulk_modulus}

    def terms(self, grid: Grid, components: tuple[str, ...]) -> list[ComplianceTerm]:
        """:func:`half_space_terms`."""
        return half_space_terms(grid, self.elastic_bulk, components)

    def stability_responses(self) -> list[CreepSpectrum]:
        """J(t) and the normal (1 - nu)/G and tangential 1/G factors (:meth:`BulkElasticMaterial.factor`;
        the normal one has the extra, shorter retardation time of G(t) + 3K) [1/Pa]."""
        bulk = self.elastic_bulk
        return [self.material.creep, bulk.factor("normal"), bulk.factor("tangential")]

    def size(self) -> tuple[int, int]:
        """2 M history fields per traction component (J and L histories), two kernels per component."""
        return 2 * self.material.creep.retardation_times.size, 2

    def result_attributes(self) -> dict[str, Any]:
        """K [Pa], nu(0) and nu(inf)."""
        k, mat = self.bulk_modulus, self.material
        nu = BulkElasticMaterial.poisson_ratio_of
        return {"bulk_modulus": float(k), "poisson_ratio_instantaneous": nu(mat.shear_modulus_instantaneous, k),
                "poisson_ratio_long_term": nu(mat.shear_modulus_long_term, k)}

    def material_summary(self) -> str:
        bulk = self.elastic_bulk
        return (f"bulk_modulus K = {self.bulk_modulus:.6g} Pa: poisson ratio nu(t) from "
                f"{bulk.poisson_ratio_instantaneous:.6g} (t = 0) to {bulk.poisson_ratio_long_term:.6g} (t = inf)")

    def contact_radius(self, load: float, shape: ContactShape, compliance_factor: float = 1.0) -> float:
        """The shape's elastic contact with G(0) and nu(0) (the material's ``poisson_ratio``), crept as
        E*/``compliance_factor`` (:func:`~viscontact.bodies.base.half_space_contact_radius`): as nu
        rises the normal compliance (1 - nu)/G creeps less than J(t), so this bounds the crept size
        from above."""
        mat = self.material
        return half_space_contact_radius(load, shape, contact_modulus(mat.shear_modulus_instantaneous,
                                                                       mat.poisson_ratio), compliance_factor)

    def contact_radius_at_approach(self, approach: float, shape: ContactShape) -> float:
        """The shape's elastic relation, whatever the moduli (Hertz: a = sqrt(R delta) [m])."""
        return shape.size_at_approach(approach)
