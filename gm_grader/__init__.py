"""gm_grader: the instructor's batch grader for the course's exercise notebooks.

Installed by the ``grader`` extra (``pip install -e ".[grader]"``) and run as ``gm-grade`` or
``python -m gm_grader``. It imports :mod:`gm_core` (the exercises' checkers); ``gm_core`` never
imports it, so a student's install never needs it.

* :mod:`.batch`: the command line and a batch's three steps, :func:`~.batch.plan`, :func:`~.batch.run`
  and :func:`~.batch.judge` (settings in :class:`~.batch.GradeSettings`);
* :mod:`.isolate`: the sandbox (bubblewrap, rlimits, a cgroup) each notebook runs in;
* :mod:`.runner`: runs one notebook cell by cell in a fresh kernel inside the sandbox;
* :mod:`.clock`: the process-tree CPU clock behind the time limits;
* :mod:`.evidence`: judges each part from the outcomes its check calls sent;
* :mod:`.report`: the rows and files of a batch's report.

Everything these processes say to each other (the runner's configuration and records, the
kernel's check announcements and evidence) is a message of :mod:`gm_core.checks.protocol`,
encoded and decoded there only.
"""
