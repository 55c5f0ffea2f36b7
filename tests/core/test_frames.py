"""Room on the frame stack (rockstudy.core.frames): the call is the plain call, and no chunk of the frame
stack is taken and given back per call inside it."""
import sys

import pytest

from rockstudy.core.frames import ROOM_SLOTS, with_frame_room

resource = pytest.importorskip("resource")


def test_the_call_is_the_plain_call():
    assert with_frame_room(divmod, 17, 5) == (3, 2)
    assert with_frame_room(dict, a=1) == {"a": 1}
    with pytest.raises(ZeroDivisionError):
        with_frame_room(divmod, 1, 0)
    assert with_frame_room.__code__.co_stacksize >= ROOM_SLOTS


def _leaf():
    return None


_leaf.__code__ = _leaf.__code__.replace(co_stacksize=256)  # a frame larger than one level of _at_depth's


def _at_depth(depth, calls):
    """Page faults of ``calls`` calls of ``_leaf`` made ``depth`` frames further down the stack."""
    if depth:
        return _at_depth(depth - 1, calls)
    before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    for _ in range(calls):
        _leaf()
    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before


def _worst(calls):
    """The most page faults of ``calls`` calls at any of 400 depths: the depths span more than one 16 KiB
    chunk of the frame stack, so that at one of them each call's frame opens a new chunk."""
    return max(_at_depth(depth, calls) for depth in range(400))


@pytest.mark.skipif(sys.implementation.name != "cpython" or sys.version_info < (3, 11) or
                    not sys.platform.startswith("linux"),
                    reason="CPython keeps frames in chunks from 3.11 on; page faults counted as Linux counts them")
@pytest.mark.plain_frames  # its plain calls must run outside the room tests/conftest.py gives the others
def test_calls_inside_the_room_take_no_new_chunk_of_the_frame_stack():
    calls = 1000
    assert _worst(calls) >= calls  # a plain call: at a chunk's end, a fresh chunk (a page fault) per call
    assert with_frame_room(_worst, calls) < calls // 10
