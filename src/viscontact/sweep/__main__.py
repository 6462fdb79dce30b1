"""``python -m viscontact.sweep SWEEP.toml --out SWEEP.nc`` is ``viscontact sweep SWEEP.toml --out SWEEP.nc``."""
import sys

if __name__ == "__main__":  # not when a spawned worker process imports this module
    from viscontact.cli import main

    sys.exit(main(["sweep", *sys.argv[1:]]))
