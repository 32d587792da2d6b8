"""``python -m gm_core.grade``: the instructors' autograder (it lives in :mod:`gm_core.checks.grade`)."""
import sys

from .checks.grade import main

if __name__ == "__main__":
    sys.exit(main())
