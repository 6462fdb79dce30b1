"""``python -m viscontact ARGS`` is ``viscontact ARGS`` (for an environment without the console script)."""
import sys

if __name__ == "__main__":  # not when a spawned worker process imports this module
    from viscontact._entry import main

    sys.exit(main())
