"""The problem: the validated physical description of one simulation (body, indenter gap, loading,
time stepping, solver and output settings), the indenter's topography and the per-step record.

Imports :mod:`viscontact.bodies` and below; free of file formats.
"""
