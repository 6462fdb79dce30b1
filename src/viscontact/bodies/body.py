"""The body of a problem: which compliance a :class:`~viscontact.problem.problem.Problem` gets, and
what its kind adds to the estimates (history sizes, stability responses)."""
from __future__ import annotations

from typing import Sequence

from viscontact.bodies.compliance import TermSubstrate, term_substrate
from viscontact.bodies.half_space import HalfSpace
from viscontact.numerics.arrays import ArrayBackend, array_backend
from viscontact.numerics.exponentials import CreepSpectrum
from viscontact.numerics.grid import Grid
from viscontact.physics.materials import Material


def substrate_for(problem, components: Sequence[str] | None = None,
                  backend: ArrayBackend | None = None) -> TermSubstrate:
    """The substrate of a :class:`~viscontact.problem.problem.Problem` (the one place that chooses it).

    ``components``: the kernels to build; by default what the transient needs: ``zz``, ``xx`` for
    partial slip, and the coupling ``xz``, ``zx`` when sliding with friction, nu < 0.5 and
    ``solver.coupling``. The steady solver asks for ``("zz",)`` (it builds its own kernels).

    ``problem.layer``: the layer's terms (:func:`layer_terms`); ``problem.bulk_modulus``: the
    half-space with nu(t) (:func:`viscontact.bodies.bulk_elastic.half_space_terms`, two histories per traction
    component); else the :class:`HalfSpace` with constant nu.

    ``backend``: where the fields live (:mod:`viscontact.numerics.arrays`); None: that of ``solver.device``.
    """
    backend = backend or array_backend(problem.solver.device)
    if components is None:
        nu = problem.material.poisson_ratio
        mode = problem.tangential.mode
        components = ["zz"] + (["xx"] if mode == "partial_slip" else [])
        if nu < 0.5 and problem.solver.coupling and mode in ("partial_slip", "gross_sliding"):
            components += ["xz", "zx"]
    if problem.layer is None and problem.bulk_modulus is None:
        return HalfSpace(problem.grid, problem.material, components, problem.time.scheme, problem.time.dt,
                         workers=problem.solver.workers, direct=problem.solver.history == "direct",
                         fft=problem.solver.fft, backend=backend)
    comps = tuple(c for c in HalfSpace.ORDER if c in set(components) | {"zz"})
    if problem.layer is not None:
        terms = layer_terms(problem.grid, problem.layer, problem.material, comps)
    else:
        from viscontact.bodies.bulk_elastic import BulkElasticMaterial, half_space_terms

        terms = half_space_terms(problem.grid, BulkElasticMaterial(problem.material, problem.bulk_modulus), comps)
    return term_substrate(problem.grid, terms, problem.time.scheme, problem.time.dt,
                          workers=problem.solver.workers, direct=problem.solver.history == "direct", backend=backend)


def _shift_node_body(problem) -> bool:
    """Whether :func:`substrate_for` builds ``problem``'s body of shift-node terms: a viscoelastic layer
    on an elastic substrate (:func:`viscontact.bodies.layer.elastic_substrate_terms`)."""
    return problem.layer is not None and problem.layer.substrate == "elastic" and not problem.material.is_elastic


def body_size(problem) -> tuple[int, int]:
    """(history fields per traction component, kernels per kernel component) of the body that
    :func:`substrate_for` builds, for the memory estimate (:func:`viscontact.running.resources.estimate`):
    M (retardation modes) and 1 for the half-space and a layer on a rigid base; 2 M and 2 with
    ``bulk_modulus`` (J and L histories); D M and D + 1 for a viscoelastic layer on an elastic
    substrate with D + 1 shift nodes (:func:`viscontact.bodies.layer.shift_nodes`)."""
    modes = problem.material.creep.retardation_times.size
    if problem.bulk_modulus is not None:
        return 2 * modes, 2
    if _shift_node_body(problem):
        from viscontact.bodies.layer import shift_nodes

        nodes = shift_nodes(problem.material).nodes.size
        return (nodes - 1) * modes, nodes
    return modes, 1


def stability_responses(problem) -> list[CreepSpectrum]:
    """Time responses [1/Pa] whose step stability bounds dt (:func:`~viscontact.numerics.schemes.stable_step_limit`):
    the shear creep J(t), and with ``problem.bulk_modulus`` the normal (1 - nu)/G and tangential
    1/G factors of :class:`~viscontact.bodies.bulk_elastic.BulkElasticMaterial` (the normal one has the extra,
    shorter retardation time of G(t) + 3K); a viscoelastic layer on an elastic substrate adds the
    responses of its shift nodes (:func:`viscontact.bodies.layer.shift_nodes`, times of G(t) + s_p)."""
    out = [problem.material.creep]
    if problem.bulk_modulus is not None:
        from viscontact.bodies.bulk_elastic import BulkElasticMaterial

        bulk = BulkElasticMaterial(problem.material, problem.bulk_modulus)
        out += [bulk.factor("normal"), bulk.factor("tangential")]
    if _shift_node_body(problem):
        from viscontact.bodies.layer import shift_nodes

        nodes = shift_nodes(problem.material)
        out += [nodes.response(problem.material, p) for p in range(nodes.nodes.size)]
    return out


def layer_terms(grid: Grid, settings, material: Material, components: Sequence[str]) -> list:
    """Compliance terms of ``material`` as a layer (``settings``: a
    :class:`~viscontact.problem.problem.LayerSettings`) on its substrate.

    Rigid base, or an elastic layer: one term per component, the unit-modulus kernel times the
    creep compliance (:func:`viscontact.bodies.layer.factored_terms`). A viscoelastic layer on an elastic
    substrate: the rigid-base terms and one kernel per shift node, each with its own creep function
    (:func:`viscontact.bodies.layer.elastic_substrate_terms`).
    """
    from viscontact.bodies.layer import Layer, elastic_substrate_terms, factored_terms, rigid_base_terms

    layer = Layer(settings.thickness, material.shear_modulus_instantaneous, material.poisson_ratio,
                  settings.substrate, settings.interface, settings.substrate_shear_modulus,
                  settings.substrate_poisson_ratio)
    comps = tuple(components)
    if layer.substrate == "rigid":
        return rigid_base_terms(grid, layer, material, comps)
    if not material.is_elastic:
        return elastic_substrate_terms(grid, layer, material, comps)
    return factored_terms(grid, layer, material.creep, comps)
