"""gm_core.checks.files.atomic_write: the one atomic write (progress record, grader results, workspace sync)."""
import os

import pytest

from gm_core.checks.files import atomic_write


@pytest.mark.parametrize("data, expected", [("é\n", "é\n".encode()), (b"\x00\xff", b"\x00\xff")])
def test_writes_text_as_utf8_and_bytes_as_they_are(tmp_path, data, expected):
    path = tmp_path / "f.json"
    path.write_bytes(b"old")
    atomic_write(path, data)
    assert path.read_bytes() == expected
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.json"]


def test_a_failed_write_keeps_the_old_file_and_leaves_no_temporary(tmp_path, monkeypatch):
    path = tmp_path / "f.json"
    path.write_bytes(b"old")

    def refuse(*args):
        raise PermissionError("read-only")

    monkeypatch.setattr(os, "replace", refuse)
    with pytest.raises(PermissionError):
        atomic_write(path, "new")
    assert path.read_bytes() == b"old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.json"]


@pytest.mark.parametrize("bad", [None, 3, ["a"]])
def test_data_that_is_not_text_or_bytes_is_refused_by_name(tmp_path, bad):
    with pytest.raises(TypeError, match="data"):
        atomic_write(tmp_path / "f", bad)
    assert list(tmp_path.iterdir()) == []
