"""Calls release the GIL: a Python thread keeps running while a render works."""
import threading
import time


def test_python_threads_run_during_a_call(sl):
    scene = sl.scene("default", width=320, height=240)
    g = sl.gbuffer(scene)
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    time.sleep(0.02)
    start = time.perf_counter()
    sl.render(scene, "rt:spp=512", gbuffer=g, cache=False)
    end = time.perf_counter()
    stop.set()
    t.join()
    during = [x for x in ticks if start < x < end]
    # Holding the GIL for the whole call would leave no tick inside it.
    assert end - start > 0.05
    assert len(during) >= 5, f"{len(during)} ticks in {end - start:.3f} s"
