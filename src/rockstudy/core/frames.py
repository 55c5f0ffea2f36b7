"""Room on CPython's frame stack for a deep computation, such as numba compiling the engine.

Since Python 3.11, CPython keeps the frames of Python calls on a stack of memory chunks of 16 KiB each:
a call whose frame does not fit in the current chunk gets a new chunk from the operating system
(``mmap``), and the chunk goes back (``munmap``) as soon as that frame returns. A computation that calls
and returns again and again right at a chunk's end pays two system calls and fresh pages for every
call. numba's compiler, whose calls run 30 to 130 frames deep, does so for hundreds of thousands of
calls wherever its depth happens to fall on a chunk's end: compiling the engine's driver took 12–14 s
of CPU there instead of 5.5 s, 1.2 million ``mmap``/``munmap`` pairs in all
(``benchmarks/compile_time.py --no-frame-room`` shows it).

:func:`with_frame_room` calls a function from a frame that takes a chunk of 2 MiB to itself, with about
1 MiB left over: every frame the function's calls push goes into that room, so no chunk is taken or
given back until the function returns. The frame's extra room is value-stack space that Python never
touches, so it costs neither time nor memory beyond an address range. On Python 3.10, whose frames are
separate objects, the call is an ordinary call with a larger frame, allocated once.
"""
from __future__ import annotations

ROOM_SLOTS = 1 << 17
"""Value-stack slots of :func:`with_frame_room`'s own frame (8 bytes each: 1 MiB). CPython gives a frame
larger than its 16 KiB chunks a chunk of the next power of two that holds it and 1,000 slots more, so this
frame gets 2 MiB and leaves about 1 MiB (130,000 slots) to the frames of the calls it makes. [-]"""


def with_frame_room(function, *args, **kwargs):
    """``function(*args, **kwargs)``, called from a frame with room for every frame its calls push
    (:data:`ROOM_SLOTS`): what it returns, or what it raises.

    Parameters
    ----------
    function : callable
        What to call; every workflow job's ``main`` and the command line run this way
        (:func:`rockstudy.studies.jobs.run`, :func:`rockstudy.cli.main`).
    *args : tuple
        Its positional arguments.
    **kwargs : dict
        Its keyword arguments.
    """
    return function(*args, **kwargs)


with_frame_room.__code__ = with_frame_room.__code__.replace(co_stacksize=ROOM_SLOTS)
