"""A store of the objects a process made last, bounded by their size: what it is asked for again is
handed back instead of being made anew."""
from __future__ import annotations

import collections
import threading
from collections.abc import Callable, Hashable
from typing import Any


class Recent:
    """The objects made last, kept for reuse up to ``limit`` in total size (the least recently used dropped
    first). Only objects that cannot change should be kept: every caller gets the same one.

    Parameters
    ----------
    limit : int
        Largest total size of the kept objects; an object larger than it is not kept. [bytes]
    size : callable
        ``size(obj)``, the size an object counts for. [bytes]
    """

    def __init__(self, limit: int, size: Callable[[Any], int]):
        self.limit = int(limit)
        self._size = size
        self._items: collections.OrderedDict[Hashable, tuple[Any, int]] = collections.OrderedDict()
        self._bytes = 0
        self._lock = threading.Lock()

    @property
    def nbytes(self) -> int:
        """Total size of the kept objects. [bytes]"""
        return self._bytes

    def __len__(self) -> int:
        return len(self._items)

    def clear(self) -> None:
        """Forget every kept object."""
        with self._lock:
            self._items.clear()
            self._bytes = 0

    def get(self, key: Hashable, make: Callable[[], Any]) -> Any:
        """The object kept under ``key``, else ``make()``, kept under ``key`` if it fits.

        Parameters
        ----------
        key : hashable
            Everything the object depends on.
        make : callable
            ``make()`` makes the object when none is kept under ``key``.
        """
        with self._lock:
            found = self._items.get(key)
            if found is not None:
                self._items.move_to_end(key)
                return found[0]
        obj = make()
        size = int(self._size(obj))
        with self._lock:
            if size <= self.limit and key not in self._items:
                self._items[key] = (obj, size)
                self._bytes += size
                while self._bytes > self.limit:
                    _, (_, old) = self._items.popitem(last=False)
                    self._bytes -= old
        return obj
