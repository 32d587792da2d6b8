"""Saying where in an answer something is, in the student's words: positions counted from 1 and
named ("the second entry", "the entry in the first row and third column"), never Python's
indices counted from 0. No gm_core imports.
"""
from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import SupportsInt

_ORDINALS = ("first", "second", "third", "fourth", "fifth", "sixth", "seventh", "eighth", "ninth",
             "tenth", "eleventh", "twelfth")


def ordinal(n: int) -> str:
    """The ordinal word of a position counted from 1: 1 -> "first", 12 -> "twelfth", 23 -> "23rd"."""
    n = int(n)
    if 1 <= n <= len(_ORDINALS):
        return _ORDINALS[n - 1]
    suffix = "th" if 10 <= n % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(n % 10, "th")
    return f"{n}{suffix}"


def _and(words: Sequence[str]) -> str:
    """"a", "a and b", "a, b and c"."""
    words = list(words)
    if len(words) <= 1:
        return "".join(words)
    return ", ".join(words[:-1]) + " and " + words[-1]


def _some(words: Sequence[str], limit: int) -> str:
    """The first ``limit`` of ``words`` joined with "and", and how many more there are."""
    if len(words) <= limit:
        return _and(words)
    return ", ".join(words[:limit]) + f" and {len(words) - limit} more"


def _squeezed(index: Iterable[SupportsInt], shape: Sequence[int]) -> tuple[list[int], list[int]]:
    """(index, shape) without the axes of length 1: a 3 x 1 column has entries, not rows."""
    pairs = [(int(i), int(n)) for i, n in zip(index, shape)]
    kept = [(i, n) for i, n in pairs if n != 1] or pairs[-1:]
    return [i for i, _ in kept], [n for _, n in kept]


def entry_name(index: Iterable[SupportsInt], shape: Sequence[int]) -> str:
    """The name of one entry of an array of ``shape`` at the 0-based numpy ``index``:
    "the second entry", "the entry in the first row and third column", "the entry in the second
    row and first column of the third matrix" (axes of length 1 are not counted)."""
    idx = [i + 1 for i in _squeezed(index, shape)[0]]
    if len(idx) == 1:
        return f"the {ordinal(idx[0])} entry"
    if len(idx) == 2:
        return f"the entry in the {ordinal(idx[0])} row and {ordinal(idx[1])} column"
    if len(idx) == 3:
        return (f"the entry in the {ordinal(idx[1])} row and {ordinal(idx[2])} column of the "
                f"{ordinal(idx[0])} matrix")
    return f"the entry at position ({', '.join(map(str, idx))}) (counting from 1)"


def differing_entries(indices: Iterable[Iterable[SupportsInt]], shape: Sequence[int],
                      limit: int = 3) -> str:
    """Which entries of an array of ``shape`` differ, from their 0-based numpy ``indices``, as a
    clause: "the second entry differs", "the first and third entries differ", "every entry
    differs", "in the second row, the first and third entries differ". Empty for no index."""
    full = tuple(int(s) for s in shape)
    idx = sorted({tuple(_squeezed(ix, full)[0]) for ix in indices})
    shape = tuple(_squeezed([0] * len(full), full)[1])
    if not idx:
        return ""
    size = 1
    for s in shape:
        size *= s
    if len(idx) == 1:
        return f"{entry_name(idx[0], shape)} differs"
    if len(idx) == size:
        return "every entry differs"
    if len(shape) == 1:
        return f"the {_some([ordinal(i[0] + 1) for i in idx], limit)} entries differ"
    if len(shape) == 2:
        rows = {i[0] for i in idx}
        cols = {i[1] for i in idx}
        if len(rows) == 1:
            (r,) = rows
            if len(idx) == shape[1]:
                return f"the whole {ordinal(r + 1)} row differs"
            return (f"in the {ordinal(r + 1)} row, the "
                    f"{_some([ordinal(i[1] + 1) for i in idx], limit)} entries differ")
        if len(cols) == 1:
            (c,) = cols
            if len(idx) == shape[0]:
                return f"the whole {ordinal(c + 1)} column differs"
            return (f"in the {ordinal(c + 1)} column, the "
                    f"{_some([ordinal(i[0] + 1) for i in idx], limit)} entries differ")
    names = [entry_name(i, shape) for i in idx]
    if len(names) > limit:
        return ", ".join(names[:limit]) + f" and {len(names) - limit} more entries differ"
    return _and(names) + " differ"


__all__ = ["ordinal", "entry_name", "differing_entries"]
