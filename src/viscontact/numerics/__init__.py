"""Numerics: grids, array backends, FFTs and convolutions, constrained and Krylov solvers, support
windows, hereditary histories, exact hereditary integrals and time schemes.

Pure functions and small value types of numpy arrays, free of I/O, plotting and of the
:class:`~viscontact.problem.problem.Problem`: the bottom layer of the package (it imports nothing
of viscontact but :mod:`viscontact.errors`).
"""
