"""The shared thread pool: the thread count as a parameter, chunks in order, nested calls serial."""

import itertools
import threading

import pytest

from sunwind.geometry.errors import InputError
from sunwind.geometry.parallel import CORES, map_ranges, thread_count, using_threads


def chunks_and_threads(n: int, min_size: int) -> tuple[list[tuple[int, int]], set[int]]:
    """The chunks ``map_ranges`` hands out over ``range(n)`` and the threads that ran them."""
    seen: set[int] = set()

    def work(lo: int, hi: int) -> tuple[int, int]:
        seen.add(threading.get_ident())
        return lo, hi

    return map_ranges(work, n, min_size), seen


def test_the_thread_count_is_what_the_block_sets_and_every_core_outside():
    assert thread_count() == CORES
    with using_threads(1):
        assert thread_count() == 1
        chunks, threads = chunks_and_threads(10_000, 10)
        assert chunks == [(0, 10_000)] and threads == {threading.get_ident()}
        with using_threads(None):  # None keeps what an enclosing block set
            assert thread_count() == 1
        with using_threads(3):
            assert thread_count() == 3
        assert thread_count() == 1
    assert thread_count() == CORES


@pytest.mark.skipif(CORES < 2, reason="needs two cores")
def test_two_threads_split_the_range_into_ordered_chunks():
    with using_threads(2):
        chunks, _ = chunks_and_threads(10_000, 10)
    assert len(chunks) > 1
    assert [lo for lo, _ in chunks] == sorted(lo for lo, _ in chunks)
    assert chunks[0][0] == 0 and chunks[-1][1] == 10_000
    assert all(a[1] == b[0] for a, b in itertools.pairwise(chunks))


def test_a_call_inside_a_chunk_runs_serially():
    inner = []

    def work(lo: int, hi: int) -> None:
        inner.append(len(map_ranges(lambda a, b: (a, b), 10_000, 10)))

    with using_threads(2):
        map_ranges(work, 1_000, 10)
    assert set(inner) == {1}


@pytest.mark.parametrize("bad", [0, -1, 1.5, True, "2"])
def test_a_thread_count_that_is_not_a_whole_number_above_zero_is_refused(bad):
    with pytest.raises(InputError, match="threads"), using_threads(bad):
        pass


def test_map_items_keeps_the_order_and_runs_the_first_item_alone():
    """The first item runs in the caller with the pool free (what it builds once it builds in
    parallel); the rest run inside chunks, where nested parallel calls run serially."""
    from sunwind.geometry.parallel import map_items, map_ranges, using_threads

    def nested_chunks(x: int) -> tuple[int, int]:
        return x, len(map_ranges(lambda lo, hi: hi - lo, 1000, 10))

    with using_threads(2):
        out = map_items(nested_chunks, list(range(9)))
    assert [x for x, _ in out] == list(range(9))
    assert out[0][1] > 1 and all(chunks == 1 for _, chunks in out[1:])
    assert map_items(nested_chunks, []) == []
