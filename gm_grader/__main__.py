"""``python -m gm_grader`` (or ``gm-grade``): the instructor's batch grader, :func:`gm_grader.batch.main`."""
import sys

from gm_grader.batch import main

if __name__ == "__main__":
    sys.exit(main())
