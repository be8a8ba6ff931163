"""The interpreter is released while baking: a second Python thread makes progress during a long
bake (bunny-loop2, 1.1 M triangles), measured against the same thread's progress on its own."""

import threading
import time

import chamfer
from conftest import MESHES


class Spinner:
    """A Python thread counting as fast as it can; it runs only while it holds the GIL."""

    def __init__(self):
        self.count = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._spin, daemon=True)

    def _spin(self):
        while not self._stop.is_set():
            self.count += 1

    def __enter__(self):
        self._thread.start()
        time.sleep(0.05)
        return self

    def __exit__(self, *_):
        self._stop.set()
        self._thread.join()


def counts_per_second(spinner, work):
    before, start = spinner.count, time.perf_counter()
    work()
    seconds = time.perf_counter() - start
    return (spinner.count - before) / seconds, seconds


def test_another_thread_runs_during_a_bake():
    mesh = MESHES / "bunny-loop2.ply.gz"
    with Spinner() as spinner:
        alone, _ = counts_per_second(spinner, lambda: time.sleep(0.5))
        during, seconds = counts_per_second(spinner, lambda: chamfer.bake(mesh))
        # The contrast, in the same run: a call into C that holds the GIL (sum over a range, one
        # bytecode) stops the thread for as long as it runs.
        held, _ = counts_per_second(spinner, lambda: sum(range(30_000_000)))
    print(
        f"\nspinner: {alone:.3g}/s alone, {during:.3g}/s during a {seconds:.2f} s bake "
        f"({during / alone:.0%}), {held:.3g}/s during a GIL-holding call ({held / alone:.0%})"
    )
    assert seconds > 0.3, "the bake must be long enough to measure"
    # The bake's threads share the machine's cores with the spinner, so it cannot count as fast as
    # alone; while the GIL is held it cannot count at all.
    assert during > 0.15 * alone, (during, alone)
    assert during > 3 * held, (during, held)
