"""What a sandbox sees, and as whom it runs: a list of folders, never the host's file system.

The sandbox's root is an empty file system of bubblewrap's own. Into it, read-only, go only:

* the system's programs and libraries (``/usr``, and ``/bin``, ``/lib``... as the host has them:
  links into ``/usr`` or folders);
* a few files of ``/etc`` the dynamic linker, Python and matplotlib read (:data:`ETC_KEPT`), and a
  ``passwd``/``group`` of two lines written here (root and the sandbox's user), never the host's;
* the Python the grader runs on (its prefixes, site-packages and the user site, if any);
* the course's two packages, ``gm_core`` and ``gm_grader`` (not the folder around them: no
  ``solutions/``, no grading folder that happens to sit beside them), as the **graded build**:
  the answer keys' folder (:data:`gm_core.checks.answer_key.KEYS_PACKAGE`) is an empty,
  read-only folder there, so no part can say what a right answer is inside (the grader judges
  with its own keys, outside);
* the run's own inbox (its staged notebook and configuration), at ``/tmp/.gm-in``.

Writable: a fresh ``/tmp`` and ``/dev/shm``, each capped at ``Limits.tmp_mb``; ``/dev`` holds
bubblewrap's device nodes and is read-only. Not there at all: the grading folder, the uploads
(the original and the staged ones), the output folder, home folders, ``/etc/shadow``, ``/var``,
``/run`` and ``/sys`` (with them the host's unix sockets; the network namespace has no others).
Every path here comes from the grader's own installation and its private folders, never from
a submission.

**As whom.** A grader running as root starts bubblewrap as root (it needs to, to reach a Python
installed under ``/root``) without a user namespace, and the sandbox's first process drops, before
anything else runs (:data:`DROP`), to a uid and gid of its own that no one on the host has
(:func:`sandbox_identity`: a fresh number for each run), with no supplementary groups, no
capabilities (an empty bounding set too) and ``no_new_privs``: it is nobody's root, its files
belong to no one, and ``RLIMIT_NPROC`` bounds its processes per notebook. A grader running as a
user runs the sandbox as that user inside a user namespace of its own (bubblewrap's default).
"""
from __future__ import annotations

import importlib.util
import os
import secrets
import shutil
import site
import subprocess
import sys
import tempfile
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from gm_core.checks.answer_key import KEYS_PACKAGE
from gm_core.checks.protocol import Limits

PKG_PARENT = Path(__file__).resolve().parents[1]   # the folder holding gm_core and gm_grader
COURSE_PACKAGES = ("gm_core", "gm_grader")
#: where the run's inbox (staged notebook, configuration, font cache) appears inside
INBOX = "/tmp/.gm-in"
#: the files and folders of /etc a sandbox may read, where the host has them
ETC_KEPT = ("ld.so.cache", "ld.so.conf", "ld.so.conf.d", "localtime", "timezone",
            "nsswitch.conf", "host.conf", "hosts", "mime.types", "fonts", "alternatives")
#: the top-level names that hold programs and libraries: links into /usr or folders
SYSTEM_TOP = ("bin", "sbin", "lib", "lib32", "lib64", "libx32")
#: the sandbox's own uids and gids, when a root grader chooses them: one nobody on the host has
UID_BASE, UID_SPAN = 2_000_000_000, 100_000_000

#: The sandbox's first process when bubblewrap runs as root: ``python -I -S -c DROP UID GID
#: PROGRAM ARGS...`` empties the capability bounding set, leaves every group, becomes UID/GID,
#: sets no_new_privs (no setuid program or file capability can give anything back) and only then
#: executes the runner. Nothing of the course or of the submission has run before it.
DROP = """\
import ctypes, os, sys
uid, gid = int(sys.argv[1]), int(sys.argv[2])
libc = ctypes.CDLL(None, use_errno=True)
with open("/proc/sys/kernel/cap_last_cap") as f:
    last = int(f.read())
for cap in range(last + 1):
    if libc.prctl(24, cap, 0, 0, 0) != 0:          # PR_CAPBSET_DROP
        raise SystemExit("gm-grade sandbox: cannot drop capability %d" % cap)
os.setgroups([])
os.setresgid(gid, gid, gid)
os.setresuid(uid, uid, uid)
if libc.prctl(38, 1, 0, 0, 0) != 0:                # PR_SET_NO_NEW_PRIVS
    raise SystemExit("gm-grade sandbox: cannot set no_new_privs")
if os.getresuid() != (uid, uid, uid) or os.getresgid() != (gid, gid, gid) or os.getgroups():
    raise SystemExit("gm-grade sandbox: the user did not change")
os.execv(sys.argv[3], sys.argv[3:])
"""


@dataclass(frozen=True)
class Identity:
    """Who a sandbox's processes are: ``uid``/``gid`` on the host; ``drop``: bubblewrap runs as
    root and the sandbox becomes them itself (:data:`DROP`), else bubblewrap's user namespace
    maps the grader's own user."""

    uid: int
    gid: int
    drop: bool


def sandbox_identity() -> Identity:
    """A fresh uid/gid for one sandbox when the grader is root, else the grader's own user."""
    if os.geteuid() == 0:
        n = UID_BASE + secrets.randbelow(UID_SPAN)
        return Identity(n, n, True)
    return Identity(os.getuid(), os.getgid(), False)


def python_roots() -> list[Path]:
    """The folders of the Python the grader runs on: prefixes, the interpreter's folder,
    site-packages and the user site (where it exists and is used)."""
    roots = [sys.prefix, sys.base_prefix, sys.exec_prefix, sys.base_exec_prefix,
             os.path.dirname(os.path.realpath(sys.executable)), *site.getsitepackages()]
    if site.ENABLE_USER_SITE:
        roots.append(site.getusersitepackages())
    return [Path(r) for r in roots if r and os.path.isdir(r)]


def course_roots(course: Path | None = None) -> list[Path]:
    """The course's packages (never the folder that holds them; ``course``: that folder, by
    default :data:`PKG_PARENT`)."""
    course = PKG_PARENT if course is None else course
    return [course / p for p in COURSE_PACKAGES if (course / p).is_dir()]


class NoAnswerKeys(RuntimeError):
    """The grader's own copy of the course has no answer keys, so it cannot judge."""


def keys_dir() -> Path:
    """The folder of the answer keys in the grader's course, which every sandbox sees empty."""
    spec = importlib.util.find_spec(KEYS_PACKAGE)
    if spec is None or not spec.submodule_search_locations:
        raise NoAnswerKeys(f"this copy of the course has no answer keys ({KEYS_PACKAGE}): grade "
                           "with the full course, not the graded build")
    return Path(list(spec.submodule_search_locations)[0]).resolve()


def _keys_dirs(course: Path | None) -> list[str]:
    """The answer keys' folders a sandbox must see empty: the grader's own, and the given
    course's (when that is another copy)."""
    found = {keys_dir()}
    if course is not None:
        other = Path(course, *KEYS_PACKAGE.split("."))
        if other.is_dir():
            found.add(other.resolve())
    return sorted(map(str, found))


def _system_paths() -> list[Path]:
    """Folders and files of the host a sandbox may read (as they are on the host)."""
    out = [Path("/usr")]
    out += [Path("/etc") / n for n in ETC_KEPT if os.path.lexists(f"/etc/{n}")]
    out += sorted(p for p in Path("/etc").glob("python3*") if p.is_dir())   # Debian's sitecustomize
    return out


def _outermost(paths: Iterable[Path]) -> list[Path]:
    """The paths (absolute, normalised) not inside another of them, sorted."""
    norm = sorted({Path(os.path.abspath(p)) for p in paths})
    return [p for p in norm if not any(o != p and o in p.parents for o in norm)]


def visible_roots(course: Path | None = None) -> list[Path]:
    """Every host folder or file a sandbox can read (outermost ones), by its real path."""
    found = [*_system_paths(), *python_roots(), *course_roots(course)]
    for top in SYSTEM_TOP:
        p = Path("/") / top
        if p.is_dir() and not p.is_symlink():
            found.append(p)
    return _outermost(Path(os.path.realpath(p)) for p in found)


def exposed(paths: Iterable[str | Path], course: Path | None = None) -> list[str]:
    """Sentences naming each of ``paths`` (the grader's own: arguments, output, staging folder)
    that lies in a folder every sandbox can read."""
    roots = visible_roots(course)
    out = []
    for p in paths:
        real = Path(os.path.realpath(p))
        for r in roots:
            if r == real or r in real.parents:
                out.append(f"{p} lies inside {r}, which every sandbox can read")
                break
    return out


def _dirs_to(dest: Path, made: set[Path], bound: Sequence[Path]) -> list[str]:
    """``--dir`` arguments creating, mode 0755, each missing ancestor of ``dest``."""
    args: list[str] = []
    for a in reversed(dest.parents):
        if a == Path("/") or a in made or a == Path("/tmp") or any(b == a or b in a.parents
                                                                    for b in bound):
            continue
        made.add(a)
        args += ["--perms", "0755", "--dir", str(a)]
    return args


def _ro_binds(paths: Iterable[Path], made: set[Path], bound: list[Path]) -> list[str]:
    """Read-only binds of ``paths`` at the same place (and at their real place, where a link
    leads there), with their missing ancestors made first."""
    args: list[str] = []
    for p in paths:
        src = Path(os.path.realpath(p))
        for dest in dict.fromkeys([Path(os.path.abspath(p)), src]):
            if any(b == dest or b in dest.parents for b in bound):
                continue
            args += _dirs_to(dest, made, bound)
            args += ["--ro-bind", str(src), str(dest)]
            bound.append(dest)
    return args


def write_identity_files(folder: Path, identity: Identity) -> tuple[Path, Path]:
    """The sandbox's ``/etc/passwd`` and ``/etc/group`` (root and its user), in ``folder``."""
    folder.mkdir(parents=True, exist_ok=True)
    passwd, group = folder / "passwd", folder / "group"
    passwd.write_text("root:x:0:0:root:/root:/usr/sbin/nologin\n"
                      f"student:x:{identity.uid}:{identity.gid}:student:/tmp/home:/usr/sbin/nologin\n")
    group.write_text(f"root:x:0:\nstudent:x:{identity.gid}:\n")
    for f in (passwd, group):
        f.chmod(0o644)
    return passwd, group


def bwrap_args(inbox: Path, etc: tuple[Path, Path], identity: Identity, limits: Limits,
               course: Path | None = None) -> list[str]:
    """bubblewrap's arguments (after ``bwrap``, before ``--``) for one run whose inbox (made
    readable to ``identity``) appears at :data:`INBOX`."""
    cap = str(limits.tmp_mb << 20)
    args = ["--ro-bind", "/usr", "/usr"]
    bound: list[Path] = [Path("/usr")]
    made: set[Path] = set()
    for top in SYSTEM_TOP:
        p = Path("/") / top
        if p.is_symlink():
            args += ["--symlink", os.readlink(p), str(p)]
        elif p.is_dir():
            args += ["--ro-bind", str(p), str(p)]
            bound.append(p)
    args += ["--perms", "0755", "--dir", "/etc"]
    made.add(Path("/etc"))
    args += _ro_binds([p for p in _system_paths() if p != Path("/usr")], made, bound)
    args += ["--ro-bind", str(etc[0]), "/etc/passwd", "--ro-bind", str(etc[1]), "/etc/group"]
    # /tmp before the binds under it (a course or venv cloned under /tmp stays visible)
    args += ["--size", cap, "--perms", "1777", "--tmpfs", "/tmp"]
    roots = _outermost([*python_roots(), *course_roots(course)])
    args += _ro_binds(roots, made, bound)
    for hidden in _keys_dirs(course):          # the graded build: no answer keys inside
        args += ["--perms", "0555", "--tmpfs", hidden, "--remount-ro", hidden]
    args += ["--ro-bind", str(inbox), INBOX]
    args += ["--proc", "/proc", "--dev", "/dev",
             "--size", cap, "--perms", "1777", "--tmpfs", "/dev/shm", "--remount-ro", "/dev"]
    if identity.drop:
        # bubblewrap as root, no user namespace: the sandbox's first process drops to the run's
        # own uid (DROP), for which it keeps only these three capabilities until then
        args += ["--unshare-ipc", "--unshare-pid", "--unshare-net", "--unshare-uts",
                 "--unshare-cgroup-try", "--cap-drop", "ALL", "--cap-add", "CAP_SETUID",
                 "--cap-add", "CAP_SETGID", "--cap-add", "CAP_SETPCAP"]
    else:
        args += ["--unshare-all", "--cap-drop", "ALL"]
    args += ["--die-with-parent", "--new-session", "--chdir", "/tmp"]
    return args


def command(inbox: Path, etc: tuple[Path, Path], identity: Identity, limits: Limits,
            program: Sequence[str], course: Path | None = None) -> list[str]:
    """The whole command running ``program`` in a sandbox (bwrap, then the drop to the run's
    user when bubblewrap runs as root)."""
    return ["bwrap", *bwrap_args(inbox, etc, identity, limits, course), "--",
            *dropped(identity, program)]


def dropped(identity: Identity, program: Sequence[str]) -> list[str]:
    """``program``, run as ``identity`` (:data:`DROP` first when it is a root grader's own uid)."""
    if not identity.drop:
        return list(program)
    return [sys.executable, "-I", "-S", "-c", DROP, str(identity.uid), str(identity.gid),
            *program]


#: What a run without a sandbox needs its own user to do: start the grader's Python, import the
#: runner and the course, and say whether the answer keys are in its reach.
_CAN_RUN = ("import gm_grader.runner, gm_core.checks.channel, nbclient\n"
            "from gm_core.checks.answer_key import keys_installed\n"
            "print('gm-keys-readable' if keys_installed() else 'gm-keys-hidden')")


def unsandboxed_user(env: dict[str, str]) -> tuple[bool, str]:
    """Without bubblewrap (``--no-sandbox``: a container per submission, as on Gradescope), a root
    grader still runs each notebook as a fresh uid of its own (:data:`DROP`), so that what only
    root may read -- the answer keys, once the kit's ``setup.sh`` has made them so -- stays out of
    the notebook's reach. (drop?, why not / what to fix): ``(True, "")`` when that user can run
    the grader's Python and the course and cannot read the keys; ``(True, note)`` when it can
    read them; ``(False, why)`` when a user of its own cannot run the grader's Python here (it lives
    in a folder only root may enter, say), and then notebooks run as the grader's own user."""
    if os.geteuid() != 0:
        return False, "the grader does not run as root, so notebooks run as its own user"
    probe = sandbox_identity()
    try:
        res = subprocess.run(dropped(probe, [sys.executable, "-c", _CAN_RUN]), env=env, cwd="/",
                             capture_output=True, text=True, timeout=120)
    except (OSError, subprocess.SubprocessError) as exc:
        return False, f"a user of its own could not be tried ({type(exc).__name__})"
    said = res.stdout.strip().splitlines()[-1:] if res.returncode == 0 else []
    if said == ["gm-keys-hidden"]:
        return True, ""
    if said == ["gm-keys-readable"]:
        return True, (f"the answer keys ({keys_dir()}) are readable by the notebooks' own user: "
                      "make them readable by root only (chmod -R go-rwx), as the Gradescope "
                      "kit's setup.sh does")
    last = (res.stderr.strip().splitlines() or ["no message"])[-1][:200]
    return False, (f"a user of its own cannot run the grader's Python here ({last}); notebooks "
                   "run as root and can read everything root can, the answer keys included")


def make_inbox(private: Path) -> Path:
    """The run's inbox in the grader's private folder: readable to the sandbox's user through
    its bind (``private`` itself stays 0700, so no one on the host reaches it)."""
    inbox = private / "in"
    inbox.mkdir()
    inbox.chmod(0o755)
    return inbox


def preflight(limits: Limits | None = None, env: dict[str, str] | None = None) -> str | None:
    """None when a sandbox made as for a notebook starts, runs as its own user and imports the
    course and the runner; otherwise why not (a sentence and bubblewrap's or Python's last
    words). Run once before a batch, so a grader that cannot work says so instead of failing
    every notebook."""
    limits = limits or Limits()
    identity = sandbox_identity()
    private = Path(tempfile.mkdtemp(prefix="gm-grade-check-"))
    try:
        os.chmod(private, 0o700)
        inbox = make_inbox(private)
        etc = write_identity_files(private / "etc", identity)
        code = ("import os, gm_core.checks.channel, gm_grader.runner, nbformat\n"
                "from gm_core.checks.answer_key import keys_installed\n"
                "assert not keys_installed(), 'the answer keys can be imported inside'\n"
                f"assert not os.listdir({str(keys_dir())!r}), 'the answer keys can be read inside'\n"
                "assert os.getuid() != 0 and os.geteuid() != 0, 'the sandbox runs as root'\n"
                f"assert os.getuid() == {identity.uid}, 'the sandbox runs as the wrong user'\n"
                f"assert os.path.isdir({INBOX!r}) and os.access('/tmp', os.W_OK)\n")
        cmd = command(inbox, etc, identity, limits, [sys.executable, "-c", code])
        run_env = {"PATH": os.environ.get("PATH", "/usr/bin:/bin"), **(env or {}),
                   "PYTHONPATH": str(PKG_PARENT), "HOME": "/tmp",
                   "PYTHONDONTWRITEBYTECODE": "1", "MPLBACKEND": "Agg"}
        try:
            res = subprocess.run(cmd, capture_output=True, timeout=120, env=run_env,
                                 stdin=subprocess.DEVNULL)
        except (OSError, subprocess.SubprocessError) as exc:
            return f"the sandbox could not be started ({type(exc).__name__}: {exc})"
        if res.returncode != 0:
            err = (res.stderr + res.stdout).decode("utf-8", "replace").strip().splitlines()
            return ("a sandbox made as for a notebook does not work here: "
                    + (" | ".join(err[-3:]) if err else f"exit status {res.returncode}"))
        return None
    finally:
        shutil.rmtree(private, ignore_errors=True)


__all__ = ["Identity", "sandbox_identity", "python_roots", "course_roots", "visible_roots",
           "exposed", "bwrap_args", "command", "make_inbox", "write_identity_files",
           "preflight", "keys_dir", "NoAnswerKeys", "dropped", "unsandboxed_user", "PKG_PARENT", "INBOX", "DROP", "ETC_KEPT"]
