"""The precompute progress hook: silent by default, steps nest, work reports to the innermost."""

from sunwind.geometry import progress
from sunwind.geometry.cache import ModelCache


class Recorder:
    def __init__(self) -> None:
        self.events: list[tuple] = []

    def begin(self, name: str) -> None:
        self.events.append(("begin", name))

    def advance(self, name: str, done: int, total: int) -> None:
        self.events.append(("advance", name, done, total))

    def end(self, name: str, seconds: float) -> None:
        assert seconds >= 0
        self.events.append(("end", name))


def test_steps_are_silent_without_a_reporter_and_nest_with_one():
    with progress.step("alone"):
        progress.advance(1, 2)  # nothing installed: nothing happens
    cache = ModelCache()
    with progress.reporting(Recorder()) as recorder:
        with progress.step("outer"):
            cache.get(("inner", 3), lambda: progress.advance(5, 4))
            progress.advance(1, 10)
        cache.get(("inner", 3), lambda: None)  # kept: no step
    assert recorder.events == [
        ("begin", "outer"),
        ("begin", "inner"),
        ("advance", "inner", 4, 4),
        ("end", "inner"),
        ("advance", "outer", 1, 10),
        ("end", "outer"),
    ]
