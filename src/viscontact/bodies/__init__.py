"""Bodies: the compliant solid under the indenter and what its surface does under a traction history.

Each kind of body is a :class:`~viscontact.bodies.base.Body` in its own module (the homogeneous
half-space :mod:`~viscontact.bodies.half_space`, the half-space with nu(t)
:mod:`~viscontact.bodies.bulk_elastic`, a layer on a base :mod:`~viscontact.bodies.layer`), chosen from
the case's description in one place (:mod:`~viscontact.bodies.registry`). A body builds compliance
terms and the :class:`~viscontact.bodies.compliance.Compliance` the contact solvers use.
Imports :mod:`viscontact.physics` and :mod:`viscontact.numerics`.
"""
