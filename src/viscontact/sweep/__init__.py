"""Parameter sweeps on a dask.distributed cluster: ``viscontact sweep SWEEP.toml --out SWEEP.nc``.

The sweep runs the Cartesian product of the values listed in a sweep file (:mod:`.spec`), one
simulation per task on a local cluster of worker processes or on an existing one
(:mod:`.execute`), and gathers the final state of every run into one Dataset and netCDF file
(:mod:`.assemble`). Figures of it: :func:`viscontact.plotting.plot_sweep`.

Example on a tiny case, without a cluster (``solver.workers`` as for a single run)::

    >>> from viscontact.sweep import SweepSpec, plan
    >>> spec = SweepSpec(base="cases/seed_table1_v0.8.toml",
    ...                  parameters={"tangential.sliding_speed": [0.01, 0.02], "grid.n": [16]})
    >>> [run.label for run in plan(spec).runs]
    ['tangential.sliding_speed=0.01, grid.n=16', 'tangential.sliding_speed=0.02, grid.n=16']
"""
from viscontact.sweep.assemble import SERIES, SUMMARIES
from viscontact.sweep.execute import cluster_client, default_workers, local_cluster, planned, runs_dir, sweep
from viscontact.sweep.spec import (
           SOLVERS,
           Plan,
           Run,
           SweepSpec,
           check_run,
           format_value,
           load_sweep,
           plan,
           run_file_name,
)

__all__ = ["SERIES", "SOLVERS", "SUMMARIES", "Plan", "Run", "SweepSpec", "check_run", "cluster_client",
           "default_workers", "format_value", "load_sweep", "local_cluster", "plan", "planned", "run_file_name",
           "runs_dir", "sweep"]
