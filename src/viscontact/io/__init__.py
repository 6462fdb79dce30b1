"""Files: the case schema (TOML) and its one-line errors, Prony tables, the result schema and netCDF
writing, streamed results, checkpoints, safe output files, the shipped cases and typed value lists.

Imports :mod:`viscontact.solvers` and below.
"""
