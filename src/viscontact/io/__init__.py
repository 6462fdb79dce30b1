"""Files: the case schema (TOML), Prony tables, the result schema and netCDF writing, streamed
results, checkpoints, safe output files and the shipped cases.

Imports :mod:`viscontact.solvers` and below.
"""
