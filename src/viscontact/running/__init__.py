"""Running: the pre-run checks (guards, resource estimates) made by the one preflight
(:func:`~viscontact.running.preflight.preflight`), the observers of a run and the Python API
(:func:`~viscontact.running.api.run`, :func:`~viscontact.running.api.run_to_file`).

Imports :mod:`viscontact.io` and below; the command line, sweeps, reproductions and plots stand
above it.
"""
