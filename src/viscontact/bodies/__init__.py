"""Bodies: what the surface of the compliant body does under a traction history.

Each kind of body (the homogeneous half-space, the half-space with nu(t), a layer on a base) turns
into compliance terms and the :class:`~viscontact.bodies.compliance.TermSubstrate` the contact
solvers use. Imports :mod:`viscontact.physics` and :mod:`viscontact.numerics`.
"""
