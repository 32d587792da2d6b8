"""Uploads are data: each submission is copied into the grader's private staging folder first.

Nothing else in the grader looks at an upload. :func:`stage` walks each submission (a folder, or
one notebook) **without following anything**: every folder is opened with ``O_NOFOLLOW`` relative
to its parent's descriptor, every entry is judged by ``lstat``, and only regular files named
``*.ipynb`` are read, through a descriptor that is checked to be the very file that was judged.
Their bytes (at most :data:`MAX_NOTEBOOK_BYTES` + 1 each) are copied under numbered names
(``0.ipynb``, ``1.ipynb``...) into a folder of the grader's, mode 0700; from then on the grader
works on those copies and on the names below, never on the upload.

What an upload may hold and what becomes of it, each with a row of the report saying why:

* a link (symbolic), to anything: not followed, not graded;
* a notebook that has names outside the batch's uploads (a hard link, say to a file of the
  grading folder): not graded (one shared between uploads is graded in each, with a note naming
  the others: that is for a human reader to judge);
* a device, a FIFO, a socket: not opened, not graded;
* a folder named like a notebook (``ex1_4.ipynb/``): not graded (and not entered);
* a name that is not UTF-8, or holds control or bidirectional-formatting characters: graded
  under a normalised name (each offending character or byte becomes U+FFFD), the row says so;
* far too many entries, folders nested too deeply, notebooks too large together: the rest is
  not looked at, and a row says so.

Workspace leftovers (:func:`leftover_reason`: checkpoints, copies, the course's updates, hidden
files) are skipped with a note and never read. Other regular files (data, pictures, notes) are
never read either: the grader runs notebooks only.
"""
from __future__ import annotations

import os
import re
import stat
import unicodedata
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

MAX_NOTEBOOK_BYTES = 50_000_000
#: entries (files and folders) looked at in one upload
MAX_ENTRIES = 20_000
#: folders within folders in one upload
MAX_DEPTH = 32
#: bytes of notebooks copied from one upload
MAX_UPLOAD_BYTES = 4 * MAX_NOTEBOOK_BYTES
#: rows for odd entries of one upload; the rest share one row
MAX_ODD_ROWS = 25

_NOFOLLOW_DIR = os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC
_NOFOLLOW_FILE = os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_NOCTTY | os.O_CLOEXEC
#: bidirectional formatting characters, which make a name read differently from what it is
_BIDI = {"\u200e", "\u200f", "\u061c", *map(chr, range(0x202A, 0x202F)), *map(chr, range(0x2066, 0x206A))}


@dataclass(frozen=True)
class StagedFile:
    """A notebook of an upload, copied: ``path`` (the grader's copy), ``rel`` (its name in the
    report: the upload's label and its path in the upload, normalised), ``inner`` (its path in
    the upload, normalised), ``note`` (why its name was changed, or '': for the student) and
    ``shared`` (the other uploads' names of the same file, or '': for the instructor only)."""

    path: Path
    rel: str
    inner: str
    note: str = ""
    shared: str = ""


@dataclass(frozen=True)
class Refusal:
    """An entry of an upload that is not graded: its name in the report and why."""

    rel: str
    why: str


@dataclass(frozen=True)
class Upload:
    """One submission, staged: its label (``alice/``, or '' for a batch of one), its notebooks
    and the entries refused."""

    prefix: str
    files: tuple[StagedFile, ...]
    refused: tuple[Refusal, ...]
    skipped: tuple[str, ...] = ()


def leftover_reason(path: Path) -> str | None:
    """Why a notebook (its path in the upload) is a workspace leftover and not a submission
    (None if it is not one)."""
    name = path.name
    if ".ipynb_checkpoints" in path.parts or name.endswith("-checkpoint.ipynb"):
        return "a Jupyter checkpoint"
    if ".course-update" in name:
        return "the course's newer version of an exercise, kept beside the student's own"
    if re.search(r"-Copy\d*\.ipynb$", name) or name.lower().startswith("copy of "):
        return "a copy of a notebook"
    if name.startswith("."):
        return "a hidden file"
    return None


def clean_name(name: str) -> tuple[str, str]:
    """(the name as the report shows it, why it differs from the file's name or '')."""
    raw = os.fsencode(name)
    try:
        text, undecodable = raw.decode("utf-8"), False
    except UnicodeDecodeError:
        text, undecodable = raw.decode("utf-8", "replace"), True
    out, control = [], False
    for ch in text:
        if unicodedata.category(ch) in ("Cc", "Cs", "Zl", "Zp") or ch in _BIDI:
            out.append("\ufffd")
            control = True
        else:
            out.append(ch)
    why = " and ".join(w for w, bad in (("is not valid UTF-8", undecodable),
                                        ("holds control or formatting characters", control)) if bad)
    return "".join(out), (f"its file name {why}" if why else "")


def _kind(mode: int) -> str:
    if stat.S_ISLNK(mode):
        return "a link"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe)"
    if stat.S_ISSOCK(mode):
        return "a socket"
    if stat.S_ISDIR(mode):
        return "a folder"
    return "not a plain file"


@dataclass
class _Walk:
    """The state of one upload's walk."""

    into: Path
    prefix: str
    counter: list[int]                       # the batch's running number for staged copies
    files: list[StagedFile] = field(default_factory=list)
    refused: list[Refusal] = field(default_factory=list)
    skipped: list[str] = field(default_factory=list)
    entries: int = 0
    copied: int = 0
    #: {(device, inode): (its number of names, indices in ``files``)} of hard-linked notebooks
    links: dict[tuple[int, int], tuple[int, list[int]]] = field(default_factory=dict)
    over: bool = False

    def refuse(self, rel: str, why: str) -> None:
        """Refuse the entry ``rel`` (a path in the upload; '' for the upload itself)."""
        name = self.prefix + rel if rel else (self.prefix.rstrip("/") or "the upload")
        self.refused.append(Refusal(name, why))

    def folder(self, dfd: int, parts: list[str], depth: int, above: str = "") -> None:
        """Walk the open folder ``dfd`` (``parts``: its path in the upload; ``above``: why a
        folder on that path was renamed, or '')."""
        try:
            names = sorted(os.listdir(dfd), key=os.fsencode)
        except OSError as exc:
            self.refuse("/".join(parts), f"the folder could not be read ({exc.strerror})")
            return
        used: set[str] = set()
        for name in names:
            if self.over:
                return
            self.entries += 1
            if self.entries > MAX_ENTRIES:
                self.refuse("/".join(parts), f"the upload holds more than {MAX_ENTRIES} "
                            "files and folders; the rest was not looked at")
                self.over = True
                return
            shown, why = clean_name(name)
            shown = _unique(shown, used)
            rel = "/".join([*parts, shown])
            try:
                st = os.stat(name, dir_fd=dfd, follow_symlinks=False)
            except OSError as exc:
                self.refuse(rel, f"it could not be looked at ({exc.strerror})")
                continue
            if stat.S_ISDIR(st.st_mode):
                if shown.endswith(".ipynb"):
                    self.refuse(rel, "it is a folder, not a notebook")
                elif depth >= MAX_DEPTH:
                    self.refuse(rel, f"folders are nested more than {MAX_DEPTH} deep; it was not "
                                "looked at")
                else:
                    self._enter(dfd, name, st, [*parts, shown], depth + 1,
                                why.replace("its file name", "the name of a folder it is in")
                                if why else above)
            elif stat.S_ISREG(st.st_mode):
                left = leftover_reason(Path(rel)) if shown.endswith(".ipynb") else None
                if left:
                    self.skipped.append(f"{self.prefix}{rel} skipped: {left}")
                elif shown.endswith(".ipynb"):
                    self.notebook(dfd, name, st, rel, why or above)
            elif stat.S_ISLNK(st.st_mode):
                self.refuse(rel, f"it is a link{_target(dfd, name)}; uploads are read from plain "
                            "files only, never through links")
            else:
                self.refuse(rel, f"it is {_kind(st.st_mode)}, not a plain file; it was not opened")

    def _enter(self, dfd: int, name: str, st: os.stat_result, parts: list[str], depth: int,
               above: str = "") -> None:
        try:
            sub = os.open(name, _NOFOLLOW_DIR, dir_fd=dfd)
        except OSError as exc:
            self.refuse("/".join(parts), f"the folder could not be opened ({exc.strerror})")
            return
        try:
            now = os.fstat(sub)
            if (now.st_dev, now.st_ino) != (st.st_dev, st.st_ino):
                self.refuse("/".join(parts), "it changed while the grader was reading it")
                return
            self.folder(sub, parts, depth, above)
        finally:
            os.close(sub)

    def notebook(self, dfd: int | None, name: str, st: os.stat_result, rel: str, why: str) -> None:
        """Copy one regular file (``name`` in the folder ``dfd``, or a path when ``dfd`` is None)."""
        if self.copied >= MAX_UPLOAD_BYTES:
            self.refuse(rel, f"the upload's notebooks together are larger than "
                        f"{MAX_UPLOAD_BYTES >> 20} MB; it was not read")
            return
        try:
            fd = os.open(name, _NOFOLLOW_FILE, dir_fd=dfd) if dfd is not None else \
                os.open(name, _NOFOLLOW_FILE)
        except OSError as exc:
            self.refuse(rel, f"it could not be opened ({exc.strerror})")
            return
        try:
            now = os.fstat(fd)
            if not stat.S_ISREG(now.st_mode) or (now.st_dev, now.st_ino) != (st.st_dev, st.st_ino):
                self.refuse(rel, "it changed while the grader was reading it")
                return
            n = self.counter[0]
            self.counter[0] += 1
            dest = self.into / f"{n}.ipynb"
            out = os.open(dest, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_CLOEXEC, 0o600)
            try:
                left = MAX_NOTEBOOK_BYTES + 1
                while left > 0:
                    chunk = os.read(fd, min(left, 1 << 20))
                    if not chunk:
                        break
                    os.write(out, chunk)
                    left -= len(chunk)
                    self.copied += len(chunk)
            finally:
                os.close(out)
        except OSError as exc:
            self.refuse(rel, f"it could not be read ({exc.strerror})")
            return
        finally:
            os.close(fd)
        note = f"{why}; it was graded under the name {rel!r}" if why else ""
        self.files.append(StagedFile(dest, self.prefix + rel, rel, note))
        if now.st_nlink > 1:
            self.links.setdefault((now.st_dev, now.st_ino), (now.st_nlink, []))[1].append(
                len(self.files) - 1)

    def settle_links(self, found: dict[tuple[int, int], list[str]]) -> None:
        """Refuse the notebooks that have names outside the batch's uploads (hard links found in
        the batch fewer times than the file has names); note those shared with another upload.
        ``found``: {(device, inode): every name of it in the batch}."""
        drop = {i for key, (nlink, idx) in self.links.items() if len(found[key]) < nlink
                for i in idx}
        for i in sorted(drop):
            f = self.files[i]
            self.refused.append(Refusal(f.rel, "it has other names elsewhere on this machine (a "
                                        "hard link); it was not read (copy the upload as plain "
                                        "files to grade it)"))
            try:
                f.path.unlink()
            except OSError:
                pass
        for key, (_, idx) in self.links.items():
            for i in set(idx) - drop:
                others = [r for r in found[key] if r != self.files[i].rel]
                if others:
                    f = self.files[i]
                    self.files[i] = StagedFile(f.path, f.rel, f.inner, f.note,
                                               f"it is the same file as {', '.join(others[:3])} "
                                               "(a hard link)")
        self.files = [f for i, f in enumerate(self.files) if i not in drop]


def _unique(name: str, used: set[str]) -> str:
    """``name``, or ``name`` with `` (2)``, `` (3)``... before its suffix when two entries of one
    folder come out with the same normalised name."""
    stem, dot, ext = name.rpartition(".")
    if not dot:
        stem, ext = name, ""
    out, n = name, 1
    while out in used:
        n += 1
        out = f"{stem} ({n})" + (f".{ext}" if dot else "")
    used.add(out)
    return out


def _target(dfd: int, name: str) -> str:
    try:
        return f" (to {clean_name(os.readlink(name, dir_fd=dfd))[0][:120]!r})"
    except OSError:
        return ""


def _label(arg: Path, many: bool) -> str:
    """The report's prefix for one command-line argument: its folder's name (normalised)."""
    if not many:
        return ""
    st = os.lstat(arg)
    name = arg.name if stat.S_ISDIR(st.st_mode) or stat.S_ISLNK(st.st_mode) else arg.parent.name
    return clean_name(name or str(arg))[0] + "/"


def stage(paths: Sequence[str | Path], into: Path) -> list[Upload]:
    """Copy the notebooks of every submission in ``paths`` into the folder ``into`` (the grader's
    own, mode 0700) and say what was refused; see the module docstring. Never follows a link,
    never opens anything but a regular file, never raises for what an upload holds."""
    into.mkdir(parents=True, exist_ok=True)
    os.chmod(into, 0o700)
    counter = [0]
    many = len(paths) > 1
    walks = []
    for arg in map(Path, paths):
        prefix = _label(arg, many)
        w = _Walk(into, prefix, counter)
        st = os.lstat(arg)
        shown, why = clean_name(arg.name or str(arg))
        if stat.S_ISDIR(st.st_mode):
            _walk_top(w, arg, st)
        elif stat.S_ISREG(st.st_mode):
            left = leftover_reason(Path(shown))
            if left:
                w.skipped.append(f"{prefix}{shown} skipped: {left}")
            elif shown.endswith(".ipynb"):
                w.notebook(None, str(arg), st, shown, why)
            else:
                w.refuse(shown, "it is not a notebook (.ipynb)")
        elif stat.S_ISLNK(st.st_mode):
            w.refuse("" if many else shown, "the upload is a link; uploads are read from plain "
                     "files and folders only, never through links")
        else:
            w.refuse("" if many else shown, f"the upload is {_kind(st.st_mode)}, not a folder or "
                     "a notebook; it was not opened")
        walks.append(w)
    found: dict[tuple[int, int], list[str]] = {}
    for w in walks:
        for key, (_, idx) in w.links.items():
            found.setdefault(key, []).extend(w.files[i].rel for i in idx)
    out = []
    for w in walks:
        w.settle_links(found)
        out.append(Upload(w.prefix, tuple(w.files), tuple(_capped(w.refused, w.prefix)),
                          tuple(w.skipped)))
    return out


def _walk_top(w: _Walk, arg: Path, st: os.stat_result) -> None:
    """Walk an upload folder given on the command line (its own name is the instructor's)."""
    try:
        fd = os.open(arg, _NOFOLLOW_DIR)
    except OSError as exc:
        w.refuse("", f"the upload could not be opened ({exc.strerror})")
        return
    try:
        now = os.fstat(fd)
        if (now.st_dev, now.st_ino) != (st.st_dev, st.st_ino):
            w.refuse("", "the upload changed while the grader was reading it")
            return
        w.folder(fd, [], 0)
    finally:
        os.close(fd)


def _capped(refused: list[Refusal], prefix: str) -> list[Refusal]:
    """At most :data:`MAX_ODD_ROWS` refusals, the rest counted in one more."""
    if len(refused) <= MAX_ODD_ROWS:
        return refused
    rest = len(refused) - MAX_ODD_ROWS
    return [*refused[:MAX_ODD_ROWS],
            Refusal(f"{prefix}...", f"{rest} more entries of the upload were not graded either "
                    "(links, devices, odd files)")]


__all__ = ["stage", "clean_name", "leftover_reason", "Upload", "StagedFile", "Refusal", "MAX_NOTEBOOK_BYTES"]
