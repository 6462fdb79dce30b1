"""Solvers: the transient stepper (seed Eqs. 5-15), the steady sliding solvers (DC-FFT and
periodic), the moving frame and the checks every solution passes.

Imports :mod:`viscontact.problem` and below.
"""
