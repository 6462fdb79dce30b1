"""Physics: viscoelastic materials (Prony series and their creep compliance,
:mod:`viscontact.physics.prony`), the Boussinesq-Cerruti influence coefficients, steady-sliding
kernels, subsurface stresses and the analytic references (Hertz, Lee-Radok, Cattaneo-Mindlin, ...).

Imports :mod:`viscontact.numerics` only.
"""
