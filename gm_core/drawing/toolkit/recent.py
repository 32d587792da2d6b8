"""What a scene computed for its last few values, by key: a slider moved back and forth (or a
student comparing two settings) finds the work done, and the picture follows at the speed of
drawing alone."""
from __future__ import annotations

from collections.abc import Callable, Hashable
from typing import Generic, TypeVar

__all__ = ["Recent"]

K = TypeVar("K", bound=Hashable)
V = TypeVar("V")


class Recent(Generic[K, V]):
    """The values made for the last ``size`` keys asked for; the one asked for least recently is
    dropped first."""

    def __init__(self, size: int) -> None:
        if not isinstance(size, int) or isinstance(size, bool) or size < 1:
            raise ValueError(f"size must be a positive integer; got {size!r}")
        self.size = size
        self._kept: dict[K, V] = {}

    def get(self, key: K, make: Callable[[], V]) -> V:
        """The value kept for ``key``, or ``make()`` (kept from now on)."""
        if key in self._kept:
            self._kept[key] = value = self._kept.pop(key)    # now the most recent
            return value
        value = make()
        while len(self._kept) >= self.size:
            del self._kept[next(iter(self._kept))]
        self._kept[key] = value
        return value

    def __len__(self) -> int:
        return len(self._kept)

    def __contains__(self, key: object) -> bool:
        return key in self._kept
