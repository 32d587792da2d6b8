"""The grader against what an upload holds and what a notebook reaches (issue 38, points 3-6).

One batch, graded as the README tells an instructor (``python -m gm_grader``, sandbox on), from
a grading folder outside ``/tmp`` that also holds an instructor's key file and a listening unix
socket. Honest classmates (alice: 1.2, bob: 1.1) sit beside:

* mallory, whose upload holds what a careless zip tool or a determined student makes: a link
  named ``ex1_1.ipynb`` to the system's ``libm`` (it once emptied that library in every sandbox),
  a link to ``/etc``, a link to the key file, a hard link to it, a FIFO, a device, a folder named
  ``ex2_2.ipynb``;
* oddnames, two honest notebooks whose names are not UTF-8 and hold control characters (one once
  made the report unwritable for everybody);
* snoop, a notebook that tries to read the key file, ``/etc/shadow`` (also through pid 1), the
  grading folder, the home folder, a classmate's upload and the staged copies, to connect to the
  socket, to write into ``/dev`` and to fill ``/dev/shm``; it checks part a only if all of that
  found nothing and ``/dev/shm`` held, and tries to send what it read back through part b's
  feedback.

Asserted: honest notebooks (the oddly named ones too) keep full marks, each odd entry gets its own
row and reason, the snoop finds nothing and leaks nothing, both report files are written, the
staging folder is gone and the exit code is 0 (all of it was the students' doing). Then, without
most kernels: the exit code is 4 when the grader is at fault (a sandbox that cannot start, a
report file it cannot write) with every other grade written, 3 when no sandbox made as for a
notebook works, 2 when the output lies where sandboxes read; staging on its own (a file two
uploads share is graded in both). Five kernel runs in the batch, two in the fault test."""
import csv
import glob
import json
import os
import shutil
import socket
import stat
import subprocess
import sys
import tempfile
import threading
import uuid
from pathlib import Path

import nbformat
import pytest

from gm_core.checks.protocol import Limits
from gm_grader import batch as _batch
from gm_grader import staging as _staging
from gm_grader import view as _view
from gm_grader.isolate import sandbox_problem

ROOT = Path(__file__).resolve().parent.parent
NO_SANDBOX = sandbox_problem()
needs_sandbox = pytest.mark.skipif(NO_SANDBOX is not None, reason=f"no sandbox: {NO_SANDBOX}")
SECRET = f"gm-secret-{uuid.uuid4().hex}"
SHM_CAP = Limits().tmp_mb << 20


def write_nb(path, cells):
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(c) for c in cells]
    with open(path, "w", encoding="utf-8") as f:
        nbformat.write(nb, f)
    return path


def honest_1_2():
    return ["import numpy as np\nfrom gm_core.checks import ex1_2",
            "ex1_2.a.check(lambda h, g: h * g)\nex1_2.b.check(lambda h, g: np.diag(h))",
            "ex1_2.check({'c': lambda h, g: np.diag(h)})"]


def libm():
    """A system library every sandbox needs (numpy links against it)."""
    for p in ("/usr/lib/x86_64-linux-gnu/libm.so.6", "/lib/x86_64-linux-gnu/libm.so.6",
              "/usr/lib/aarch64-linux-gnu/libm.so.6", "/usr/lib64/libm.so.6", "/lib64/libm.so.6"):
        if os.path.exists(p):
            return p
    found = glob.glob("/usr/lib*/**/libm.so*", recursive=True)
    return found[0] if found else "/usr/lib/libm.so.6"


def home_allowed():
    """Names of the grader's home folder a sandbox may list: those leading to its Python."""
    home = Path(os.path.expanduser("~")).resolve()
    return sorted({p.relative_to(home).parts[0] for p in _view.python_roots()
                   if home in Path(os.path.realpath(p)).parents})


def snoop_cells(key, sock, grading, alice, staging):
    home = os.path.expanduser("~")
    return [
        "import glob, os, socket\nimport numpy as np\nfrom gm_core.checks import ex1_2\n"
        f"KEY, SOCK, GRADING, ALICE, STAGING = {str(key)!r}, {str(sock)!r}, {str(grading)!r}, "
        f"{str(alice)!r}, {str(staging)!r}\nLIBM = {libm()!r}\n"
        f"HOME, ALLOWED = {home!r}, {home_allowed()!r}\n"
        "found = []\n"
        "def attempt(what, f):\n    try:\n        r = f()\n    except Exception:\n        return\n"
        "    if r:\n        found.append((what, str(r)[:200]))\n"
        "attempt('key', lambda: open(KEY).read())\n"
        "attempt('shadow', lambda: open('/etc/shadow').read())\n"
        "attempt('shadow through pid 1', lambda: open('/proc/1/root/etc/shadow').read())\n"
        "attempt('grading folder', lambda: os.listdir(GRADING))\n"
        "attempt('home', lambda: sorted(set(os.listdir(HOME)) - set(ALLOWED)))\n"
        "attempt('classmate', lambda: open(ALICE).read())\n"
        "attempt('staged copies', lambda: os.listdir(STAGING) + glob.glob('/tmp/gm-stage-*'))\n"
        "def connect():\n    s = socket.socket(socket.AF_UNIX)\n    s.settimeout(2)\n"
        "    s.connect(SOCK)\n    return 'connected'\n"
        "attempt('socket', connect)\n"
        "attempt('root', lambda: 'uid 0' if 0 in os.getresuid() else '')\n"
        "attempt('/dev written', lambda: open('/dev/gm-x', 'w').write('x'))\n"
        "attempt('libm gone', lambda: '' if os.path.isfile(LIBM) and os.path.getsize(LIBM) "
        "else 'libm missing')\n"
        "n = 0\ntry:\n    for i in range(4096):\n        with open(f'/dev/shm/f{i}', 'wb') as f:\n"
        "            for _ in range(16):\n                f.write(bytes(1 << 20))\n"
        "                n += 1 << 20\nexcept OSError:\n    pass\n"
        f"shm_held = {SHM_CAP - (32 << 20)} <= n <= {SHM_CAP}      # usable, up to its cap\n"
        "for p in glob.glob('/dev/shm/f*'):\n    os.remove(p)",
        "if not found and shm_held:\n    ex1_2.a.check(lambda h, g: h * g)",
        "leaked = repr(found)\ntry:\n    leaked += open(KEY).read()\nexcept OSError as e:\n"
        "    leaked += repr(e)\n"
        "def tell(h, g):\n    raise RuntimeError('LEAK ' + leaked)\n"
        "ex1_2.b.check(tell)\nex1_2.c.check(lambda h, g: np.diag(h))"]


class Listener:
    """A unix socket in the grading folder, world-writable, noting every connection."""

    def __init__(self, path):
        self.sock = socket.socket(socket.AF_UNIX)
        self.sock.bind(str(path))
        os.chmod(path, 0o777)
        self.sock.listen(8)
        self.sock.settimeout(0.5)
        self.connections = 0
        self.stop = False
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self):
        while not self.stop:
            try:
                conn, _ = self.sock.accept()
            except OSError:
                continue
            self.connections += 1
            conn.close()

    def close(self):
        self.stop = True
        self.thread.join(timeout=5)
        self.sock.close()


@pytest.fixture(scope="module")
def uploads():
    grading = Path(tempfile.mkdtemp(prefix="gm-grading-", dir="/var/tmp"))
    listener = None
    try:
        key = grading / "instructor-key.pem"
        key.write_text(SECRET)
        key.chmod(0o644)                     # readable by anyone on the host: only the view protects it
        listener = Listener(grading / "host.sock")
        subs = grading / "submissions"
        for who in ("alice", "bob", "mallory", "oddnames", "snoop"):
            (subs / who).mkdir(parents=True)
        alice = write_nb(subs / "alice" / "ex1_2.ipynb", honest_1_2())
        shutil.copyfile(ROOT / "solutions" / "ex1_1.ipynb", subs / "bob" / "ex1_1.ipynb")
        m = subs / "mallory"
        (m / "ex1_1.ipynb").symlink_to(libm())
        (m / "etc").symlink_to("/etc")
        (m / "ex1_3.ipynb").symlink_to(key)
        os.link(key, m / "ex3_1.ipynb")
        os.mkfifo(m / "ex2_1.ipynb")
        (m / "ex2_2.ipynb").mkdir()
        try:
            os.mknod(m / "ex3_2.ipynb", 0o666 | stat.S_IFCHR, os.makedev(1, 3))
            device = True
        except OSError:
            device = False
        odd = os.fsencode(subs / "oddnames")
        write_nb(os.fsdecode(odd + b"/ex1_2 \xff\xfe.ipynb"), honest_1_2())
        shutil.copyfile(ROOT / "solutions" / "ex1_1.ipynb", subs / "oddnames" / "ex1_1\x1b[2J\n.ipynb")
        staging = grading / "tmp"                          # the grader's TMPDIR: staging, inboxes
        staging.mkdir()
        write_nb(subs / "snoop" / "ex1_2.ipynb",
                 snoop_cells(key, grading / "host.sock", grading, alice, staging))
        out = grading / "out"
        env = {**os.environ, "PYTHONPATH": str(ROOT), "TMPDIR": str(staging)}
        res = subprocess.run([sys.executable, "-m", "gm_grader", *sorted(subs.iterdir()),
                              "--out", str(out), "--jobs", "2", "--memory", "2048"],
                             capture_output=True, cwd=grading, env=env, timeout=900)
        listener.close()
        raw = {f: (out / f).read_bytes() for f in ("results.json", "grades.csv")
               if (out / f).exists()}
        yield {"res": res, "raw": raw, "out": out, "device": device,
               "rows": list(csv.DictReader(open(out / "grades.csv", encoding="utf-8")))
               if "grades.csv" in raw else [],
               "results": json.loads(raw["results.json"]) if "results.json" in raw else {},
               "connections": listener.connections, "staging_left": sorted(os.listdir(staging)),
               "key": key, "libm": libm()}
    finally:
        if listener is not None:
            listener.close()
        shutil.rmtree(grading, ignore_errors=True)


def rows_of(up, who):
    return [r for r in up["rows"] if r["notebook"].split("/")[0] == who]


def scores(up, who):
    return {(r["notebook"].split("/", 1)[1], r["part"]): float(r["score"]) for r in rows_of(up, who)}


@needs_sandbox
def test_odd_uploads_are_the_students_doing_and_both_reports_are_written(uploads):
    res = uploads["res"]
    out = res.stdout.decode("utf-8", "replace") + res.stderr.decode("utf-8", "replace")
    assert res.returncode == 0, out
    assert set(uploads["raw"]) == {"results.json", "grades.csv"}, out
    uploads["raw"]["results.json"].decode("utf-8")            # valid UTF-8, whatever the names
    uploads["raw"]["grades.csv"].decode("utf-8")
    assert "GRADER FAULT" not in out
    assert uploads["staging_left"] == []                      # staged copies and inboxes removed
    assert uploads["results"]["score"] == pytest.approx(sum(float(r["score"]) for r in uploads["rows"]))


@needs_sandbox
def test_honest_classmates_keep_full_marks(uploads):
    assert scores(uploads, "alice") == {("ex1_2.ipynb", p): 2.0 for p in "abc"}
    assert scores(uploads, "bob") == {("ex1_1.ipynb", "a"): 1.0, ("ex1_1.ipynb", "b"): 1.0}
    assert os.path.exists(uploads["libm"])                    # and the library is untouched


@needs_sandbox
def test_odd_names_are_graded_under_a_normalised_name_that_says_so(uploads):
    rows = rows_of(uploads, "oddnames")
    assert {r["notebook"] for r in rows} == {"oddnames/ex1_2 \ufffd\ufffd.ipynb",
                                             "oddnames/ex1_1\ufffd[2J\ufffd.ipynb"}, rows
    assert all(float(r["score"]) == float(r["max_score"]) > 0 for r in rows), rows
    for r in rows:
        why = "not valid UTF-8" if "ex1_2" in r["notebook"] else "control or formatting characters"
        assert why in r["message"] and "graded under the name" in r["message"], r


@needs_sandbox
def test_each_link_device_fifo_and_folder_gets_its_own_row_and_reason(uploads):
    rows = {r["notebook"].split("/", 1)[1]: r for r in rows_of(uploads, "mallory")}
    want = {"ex1_1.ipynb": f"a link (to {uploads['libm']!r})", "etc": "a link (to '/etc')",
            "ex1_3.ipynb": f"a link (to {str(uploads['key'])!r})",
            "ex3_1.ipynb": "other names elsewhere on this machine (a hard link)",
            "ex2_1.ipynb": "a FIFO", "ex2_2.ipynb": "a folder, not a notebook"}
    if uploads["device"]:
        want["ex3_2.ipynb"] = "a device"
    assert set(rows) == set(want), sorted(rows)
    for name, why in want.items():
        r = rows[name]
        assert r["message"].startswith("Not graded: ") and why in r["message"], r
        assert float(r["score"]) == float(r["max_score"]) == 0.0
        assert name in uploads["results"]["output"]           # and the instructor's summary names it


@needs_sandbox
def test_nothing_outside_the_submission_is_readable_or_reachable_from_inside(uploads):
    rows = {r["part"]: r for r in rows_of(uploads, "snoop")}
    # part a is checked only when every attempt found nothing and /dev/shm held at its cap
    assert {p: float(r["score"]) for p, r in rows.items()} == {"a": 2.0, "b": 0.0, "c": 2.0}, rows
    assert uploads["connections"] == 0
    for data in uploads["raw"].values():
        assert SECRET.encode() not in data                    # nothing read, nothing leaked


# ------------------------------------------------------------------ the grader's own faults
@needs_sandbox
def test_a_sandbox_that_cannot_start_is_the_graders_fault_and_the_rest_is_graded(
        tmp_path, monkeypatch, capsys):
    subs = tmp_path / "subs"
    for who in ("alice", "bob"):
        (subs / who).mkdir(parents=True)
        write_nb(subs / who / "ex1_2.ipynb", [f"# {who}", *honest_1_2()])
    real = _view.command
    alice_tries = []

    def broken_for_bob(inbox, *args, **kw):
        """bob's sandbox never starts; alice's fails once (a busy machine), then starts."""
        cmd = real(inbox, *args, **kw)
        nb = inbox / "submission.ipynb"                       # (the preflight has none)
        text = nb.read_text() if nb.exists() else ""
        if "# alice" in text:
            alice_tries.append(1)
        if "# bob" in text or ("# alice" in text and len(alice_tries) == 1):
            cmd.insert(1, "--gm-no-such-option")              # bwrap refuses to start
        return cmd

    monkeypatch.setattr(_view, "command", broken_for_bob)
    code = _batch.main([str(subs / "alice"), str(subs / "bob"), "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 4, err
    assert "GRADER FAULT: bob/ex1_2.ipynb: the sandbox or the grader's runner could not start" in err
    assert f"tried {_batch.STARTUP_ATTEMPTS} times" in err
    assert "gm-no-such-option" in err                         # bubblewrap's own words
    assert "GRADER FAULT: alice" not in err and len(alice_tries) >= 2
    rows = list(csv.DictReader(open(tmp_path / "out" / "grades.csv", encoding="utf-8")))
    by = {(r["notebook"].split("/")[0], r["part"]): r for r in rows}
    assert all(float(by["alice", p]["score"]) == 2.0 for p in "abc"), rows
    for p in "abc":
        msg = by["bob", p]["message"]
        assert "fault in the grader, not in your notebook" in msg and "stopped" not in msg, msg
    assert "GRADER FAULT" in json.loads((tmp_path / "out" / "results.json").read_text())["output"]


def test_a_report_file_that_cannot_be_written_is_the_graders_fault(tmp_path, capsys):
    (tmp_path / "empty").mkdir()
    out = tmp_path / "out"
    (out / "results.json").mkdir(parents=True)                 # in the way of the file
    code = _batch.main([str(tmp_path / "empty"), "--out", str(out), "--no-sandbox"])
    err = capsys.readouterr().err
    assert code == 4 and "results.json could not be written" in err, err
    assert (out / "grades.csv").read_text().startswith("notebook,exercise,part")   # written anyway


def test_a_report_with_names_that_are_not_utf8_is_written(tmp_path):
    from gm_grader import report
    bad = os.fsdecode(b"ex1_1\xff.ipynb")                       # a lone surrogate, as Python reads it
    rows = [{"notebook": bad, "exercise": "1.1", "part": "a", "status": "passed", "score": 1.0,
             "max_score": 1.0, "message": f"checked in {bad}"}]
    res = report.write(rows, tmp_path, message=bad)
    assert res["tests"][0]["name"].startswith("ex1_1?.ipynb")
    assert "ex1_1?.ipynb" in (tmp_path / "grades.csv").read_text(encoding="utf-8")


@needs_sandbox
def test_no_working_sandbox_means_refusal_with_the_cause(tmp_path, monkeypatch, capsys):
    (tmp_path / "empty").mkdir()
    monkeypatch.setattr(_view, "INBOX", "/usr/gm-no-inbox")    # a mount bubblewrap cannot make
    code = _batch.main([str(tmp_path / "empty"), "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 3 and "a sandbox made as for a notebook does not work here" in err, err
    assert "bwrap" in err and "gm-no-inbox" in err and not (tmp_path / "out").exists()


@needs_sandbox
def test_the_preflight_runs_as_a_user_of_its_own():
    assert _view.preflight() is None
    a, b = _view.sandbox_identity(), _view.sandbox_identity()
    if os.geteuid() == 0:
        assert a.drop and a.uid >= _view.UID_BASE and a.uid != 0 and a.gid == a.uid
    else:
        assert not a.drop and a.uid == os.getuid()
    assert (a.uid == b.uid) == (os.geteuid() != 0)             # a root grader: one per sandbox


def test_output_or_uploads_where_every_sandbox_reads_are_refused(tmp_path, capsys):
    course = tmp_path / "course"
    (course / "gm_core").mkdir(parents=True)
    assert _view.exposed([course / "gm_core" / "out", "/usr/share/x", tmp_path / "out"],
                         course=course) == [
        f"{course / 'gm_core' / 'out'} lies inside {course / 'gm_core'}, which every sandbox can read",
        "/usr/share/x lies inside /usr, which every sandbox can read"]
    if NO_SANDBOX is None:
        (tmp_path / "empty").mkdir()
        code = _batch.main([str(tmp_path / "empty"), "--out", str(ROOT / "gm_core" / "gm-out")])
        assert code == 2 and "which every sandbox can read" in capsys.readouterr().err
        assert not (ROOT / "gm_core" / "gm-out").exists()


# ------------------------------------------------------------------ staging, without kernels
def test_staging_copies_plain_notebooks_and_follows_nothing(tmp_path):
    a, m = tmp_path / "alice", tmp_path / "mallory"
    a.mkdir()
    m.mkdir()
    (a / "ex1_1.ipynb").write_text("{}")
    os.link(a / "ex1_1.ipynb", m / "ex1_1.ipynb")             # shared by two uploads
    (m / "sub").mkdir()
    (m / "sub" / "ex1_2.ipynb").write_text('{"cells": []}')
    (m / "up").symlink_to("..")                               # a loop, never entered
    (m / ".ipynb_checkpoints").mkdir()
    (m / ".ipynb_checkpoints" / "ex1_1-checkpoint.ipynb").write_text("{}")
    (m / "big.ipynb").write_bytes(b" " * (_staging.MAX_NOTEBOOK_BYTES + 100))
    into = tmp_path / "stage"
    ups = _staging.stage([a, m], into)
    files = {f.rel: f for u in ups for f in u.files}
    assert set(files) == {"alice/ex1_1.ipynb", "mallory/ex1_1.ipynb", "mallory/sub/ex1_2.ipynb",
                          "mallory/big.ipynb"}
    assert "mallory/ex1_1.ipynb" in files["alice/ex1_1.ipynb"].shared   # alice keeps her notebook
    assert files["alice/ex1_1.ipynb"].note == ""                         # and is told nothing odd
    assert files["mallory/big.ipynb"].path.stat().st_size == _staging.MAX_NOTEBOOK_BYTES + 1
    for f in files.values():
        assert f.path.parent == into and not f.path.is_symlink()
        assert stat.S_IMODE(f.path.stat().st_mode) == 0o600
    assert stat.S_IMODE(into.stat().st_mode) == 0o700
    refused = {r.rel: r.why for u in ups for r in u.refused}
    assert set(refused) == {"mallory/up"} and "link (to '..')" in refused["mallory/up"]
    assert any("checkpoint" in s for u in ups for s in u.skipped)


def test_names_are_normalised_and_told(tmp_path):
    assert _staging.clean_name("ex1_4.ipynb") == ("ex1_4.ipynb", "")
    assert _staging.clean_name(os.fsdecode(b"ex1_4\xff.ipynb")) == (
        "ex1_4\ufffd.ipynb", "its file name is not valid UTF-8")
    shown, why = _staging.clean_name("ex1_4\u202egnp.ipynb\n")
    assert shown == "ex1_4\ufffdgnp.ipynb\ufffd" and "control or formatting" in why
    assert _staging.clean_name("résumé ex1_4.ipynb") == ("résumé ex1_4.ipynb", "")
    up = tmp_path / "u"
    up.mkdir()
    for raw in (b"ex1_1\xff.ipynb", b"ex1_1\xfe.ipynb"):     # both normalise to one name
        (Path(os.fsdecode(os.fsencode(up) + b"/" + raw))).write_text("{}")
    (staged,) = _staging.stage([up], tmp_path / "stage")
    assert sorted(f.rel for f in staged.files) == ["ex1_1\ufffd (2).ipynb", "ex1_1\ufffd.ipynb"]


def test_an_upload_that_is_a_link_or_a_fifo_is_refused_whole(tmp_path):
    (tmp_path / "real").mkdir()
    (tmp_path / "real" / "ex1_1.ipynb").write_text("{}")
    (tmp_path / "alias").symlink_to(tmp_path / "real")
    os.mkfifo(tmp_path / "pipe.ipynb")
    ups = _staging.stage([tmp_path / "alias", tmp_path / "pipe.ipynb"], tmp_path / "stage")
    assert [u.files for u in ups] == [(), ()]
    assert ups[0].refused[0].rel == "alias" and "is a link" in ups[0].refused[0].why
    assert "FIFO" in ups[1].refused[0].why
