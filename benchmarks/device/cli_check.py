"""The command line on the GPU: ``viscontact run`` and ``viscontact steady`` of a shipped case with
``--set solver.device="gpu"`` beside the same commands on the CPU, timed; their result files compared.

    python benchmarks/device/cli_check.py                     # seed Table 1, v = 0.8 a0/tau, 256^2
    python benchmarks/device/cli_check.py --case cases/creep_indentation.toml --set grid.n=512

Both runs solve to the case's tolerance (1e-8: the relative change of p in a CG iteration), so their
fields differ by what two stopping points of that tolerance differ by (~1e-7 of the peak), not by
round-off (``tests/unit/test_array_seam.py`` compares runs solved to round-off). Exits 1 where a
command fails or a pressure field differs by more than 1e-6 of its peak.
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import xarray as xr

AGREEMENT = 1e-6  # of the peak pressure: 100 times the solver tolerance


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", default="cases/seed_table1_v0.8.toml")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    args = parser.parse_args()
    folder = Path(tempfile.mkdtemp(prefix="viscontact_cli_"))
    print("| command | device | wall [s] | max dp / peak against the CPU | mu_app at the end |")
    print("|---|---|---|---|---|")
    worst = 0.0
    for command in ("run", "steady"):
        files = {}
        for device in ("cpu", "gpu"):
            files[device] = folder / f"{command}_{device}.nc"
            sets = [f"--set={s}" for s in args.set] + [f'--set=solver.device="{device}"']
            start = time.perf_counter()
            done = subprocess.run([sys.executable, "-m", "viscontact", command, args.case, "--out", str(files[device]),
                                   "--quiet", *sets], env=os.environ, capture_output=True, text=True)
            wall = time.perf_counter() - start
            if done.returncode:
                print(f"viscontact {command} on the {device}: status {done.returncode}: {done.stderr.strip()}")
                return 1
            with xr.open_dataset(files[device]) as result, xr.open_dataset(files["cpu"]) as cpu:
                pressure, reference = result["pressure"].values, cpu["pressure"].values
                diff = float(np.max(np.abs(pressure - reference)) / np.max(np.abs(reference)))
                mu = float(np.ravel(result["mu_app"].values)[-1]) if "mu_app" in result else float("nan")
            worst = max(worst, diff)
            print(f"| viscontact {command} | {device} | {wall:.1f} | {diff:.1e} | {mu:.6f} |")
    print(f"largest difference {worst:.1e} of the peak (at most {AGREEMENT:.0e})")
    return int(worst > AGREEMENT)


if __name__ == "__main__":
    sys.exit(main())
