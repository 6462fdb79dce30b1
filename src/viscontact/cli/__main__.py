"""``python -m viscontact.cli ARGS`` is ``viscontact ARGS`` (:func:`viscontact.cli.main`, as before the
command line became a package)."""
import sys

if __name__ == "__main__":  # not when a spawned worker process imports this module
    from viscontact.cli import main

    sys.exit(main())
