"""Calls release the GIL: a Python thread keeps running while a render works."""
import threading
import time


def test_python_threads_run_during_calls(sl):
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
    # Calls until they have lasted 0.2 s in all, however fast this machine traces: the ticks
    # counted are the ones stamped strictly inside a call.
    spans, inside = [], 0.0
    while inside < 0.2 and len(spans) < 500:
        start = time.perf_counter()
        sl.render(scene, "rt:spp=64", gbuffer=g, cache=False)
        end = time.perf_counter()
        spans.append((start, end))
        inside += end - start
    stop.set()
    t.join()
    during = sum(1 for x in ticks for (a, b) in spans if a < x < b)
    # Holding the GIL for each call would leave no tick inside any of them.
    assert during >= 5, f"{during} ticks in {inside:.3f} s of {len(spans)} calls"
