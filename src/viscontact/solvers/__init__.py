"""Solvers: the transient stepper (seed Eqs. 5-15), the steady sliding solvers (DC-FFT and
periodic), the moving frame, the checks every solution passes and the one-point estimate of the time
scheme's error.

Imports :mod:`viscontact.problem` and below.
"""
