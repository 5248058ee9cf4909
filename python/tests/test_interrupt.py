# The GIL is released while C++ traces, and Ctrl-C stops a long trace with KeyboardInterrupt.
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import pytest

import coxmesh


def test_other_threads_run_during_a_trace():
    stamps = []
    done = threading.Event()

    def count():
        n = 0
        while not done.is_set():
            n += 1
            if n % 1000 == 0:
                stamps.append(time.perf_counter())

    thread = threading.Thread(target=count)
    thread.start()
    time.sleep(0.05)
    t0 = time.perf_counter()
    mesh = coxmesh.trace(preset="sphere", edge_length=0.02, threads=1)
    t1 = time.perf_counter()
    done.set()
    thread.join()
    assert mesh.traced_simplices > 100_000
    margin = 0.1 * (t1 - t0)
    inside = [s for s in stamps if t0 + margin < s < t1 - margin]
    assert len(inside) >= 20, f"{len(inside)} progress marks of the other thread during a {t1 - t0:.2f} s trace"


CHILD = textwrap.dedent("""
    import sys, numpy as np, coxmesh
    kind = sys.argv[1]
    print("ready", flush=True)
    try:
        if kind == "preset":
            coxmesh.trace(preset="sphere", edge_length=0.0015, threads=1, max_simplices=10**9)
        else:
            coxmesh.trace(function=lambda X: (X * X).sum(axis=1) - 1, dim=3, seeds=[[1, 0, 0]],
                          edge_length=0.002, max_simplices=10**9)
    except KeyboardInterrupt:
        print("interrupted", flush=True)
        sys.exit(3)
    print("finished", flush=True)
""")


@pytest.mark.parametrize("kind", ["preset", "callable"])
def test_ctrl_c_stops_a_long_trace(kind):
    child = subprocess.Popen([sys.executable, "-c", CHILD, kind], stdout=subprocess.PIPE, text=True,
                             env=dict(os.environ))
    try:
        assert child.stdout.readline().strip() == "ready"
        time.sleep(1.0)  # inside the trace
        assert child.poll() is None, "the trace ended too soon to be interrupted"
        sent = time.perf_counter()
        child.send_signal(signal.SIGINT)
        out, _ = child.communicate(timeout=10)
        elapsed = time.perf_counter() - sent
    finally:
        if child.poll() is None:
            child.kill()
    assert "interrupted" in out and child.returncode == 3
    assert elapsed < 2.0, f"KeyboardInterrupt took {elapsed:.2f} s"
