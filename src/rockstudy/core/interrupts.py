"""Ctrl-C inside compiled code: seen as the :class:`KeyboardInterrupt` it is.

numba's compiled code that calls back into Python while Ctrl-C is pending (to build an exception object, or a
progress message) gets the interrupt there and reports it as a ``SystemError`` ("returned a result with an
exception set") whose causes hold the :class:`KeyboardInterrupt`. :func:`interruptible` turns that back into
a :class:`KeyboardInterrupt`, so that a user of the library and the command line see what they did.
"""
from __future__ import annotations

from contextlib import contextmanager


def caused_by_interrupt(exc: BaseException | None) -> bool:
    """Whether ``exc`` is, or comes of, a :class:`KeyboardInterrupt`.

    Parameters
    ----------
    exc : BaseException
        The exception raised; its ``__cause__`` and ``__context__`` chain is followed (once per exception).
    """
    seen = set()
    while exc is not None and id(exc) not in seen:
        if isinstance(exc, KeyboardInterrupt):
            return True
        seen.add(id(exc))
        exc = exc.__cause__ or exc.__context__
    return False


@contextmanager
def interruptible():
    """Run the block; a ``SystemError`` that comes of Ctrl-C leaves it as a :class:`KeyboardInterrupt`."""
    try:
        yield
    except SystemError as exc:
        if caused_by_interrupt(exc):
            raise KeyboardInterrupt from None
        raise
