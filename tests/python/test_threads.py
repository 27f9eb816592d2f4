"""Long calls behave as a Python user expects: the GIL is released, Ctrl-C (SIGINT) stops a bake
within a second and leaves nothing running, and progress callbacks report and can cancel."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import prtkit

# About a minute of work on two cores: long enough that only cancelling ends it in time.
LONG = dict(mode="shadowed", samples=1 << 16)


@pytest.fixture(scope="module")
def big():
    return prtkit.load_mesh("builtin:sphere-plane")


def os_threads():
    return len(os.listdir("/proc/self/task"))


def cpu_seconds():
    t = os.times()
    return t.user + t.system


def test_sigint_cancels_a_bake_within_a_second(big):
    prtkit.bake(big, samples=64)  # start every worker of the pool before counting threads
    threads_before, python_before = os_threads(), threading.active_count()
    sent = []

    def interrupt():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(0.3, interrupt)
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        prtkit.bake(big, **LONG)
    raised = time.monotonic()
    timer.join()
    assert sent, "the bake ended before the signal was sent"
    assert raised - sent[0] < 1.0, f"KeyboardInterrupt {raised - sent[0]:.2f} s after SIGINT"
    assert raised - start < 5.0
    # Nothing is left running: no extra thread, no CPU spent afterwards.
    # TBB may retire idle workers, or start the rest of its pool during the long bake: at most
    # the main thread and get_threads() - 1 workers remain, never the call's helper thread.
    assert threading.active_count() == python_before
    assert os_threads() <= max(threads_before, prtkit.get_threads()), (threads_before,
                                                                       prtkit.get_threads())
    c0 = cpu_seconds()
    time.sleep(0.3)
    assert cpu_seconds() - c0 < 0.1
    # And the next call runs normally (the cancel flag was cleared).
    assert prtkit.bake(big, samples=4).shape == (big.vertex_count, 9)


def test_ctrl_c_stops_the_bakes_of_other_threads_too(big):
    # As in prt: Ctrl-C stops every prtkit call in progress; another thread's raises Cancelled.
    errors = []

    def other():
        try:
            prtkit.bake(big, **LONG)
        except prtkit.Cancelled as e:
            errors.append(e)

    th = threading.Thread(target=other)
    th.start()
    time.sleep(0.2)
    timer = threading.Timer(0.2, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        prtkit.bake(big, **LONG)
    th.join(timeout=5)
    timer.join()
    assert not th.is_alive() and len(errors) == 1


def test_the_gil_is_released_during_a_bake(big):
    counts = []
    stop = threading.Event()

    def count():
        n = 0
        while not stop.is_set():
            n += 1
            if n % 1000 == 0:
                counts.append((time.monotonic(), n))

    th = threading.Thread(target=count)
    th.start()
    time.sleep(0.05)
    t0 = time.monotonic()
    prtkit.bake(big, mode="shadowed", samples=1024)
    t1 = time.monotonic()
    stop.set()
    th.join()
    during = [c for c in counts if t0 <= c[0] <= t1]
    assert t1 - t0 > 0.2, "the bake was too short to tell"
    # The Python thread counted all through the bake, not only before and after it.
    assert len(during) > 50
    gaps = np.diff([t0] + [c[0] for c in during] + [t1])
    assert gaps.max() < 0.5 * (t1 - t0)


def test_a_progress_callback_reports_and_can_cancel(big):
    seen = []
    prtkit.bake(big, samples=256, progress=seen.append)
    assert seen and seen[-1] == 1.0 and all(0 <= f <= 1 for f in seen)
    assert seen == sorted(seen)

    # Returning False cancels: the library stops at its next report (every 1/256th of the work).
    start = time.monotonic()
    with pytest.raises(prtkit.Cancelled):
        prtkit.bake(big, **LONG, progress=lambda f: False)
    assert time.monotonic() - start < 5
    assert isinstance(prtkit.Cancelled("x"), prtkit.Error)


def test_an_exception_in_the_callback_propagates(big):
    def boom(f):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        prtkit.bake(big, **LONG, progress=boom)


def test_a_tqdm_bar(big, capsys):
    pytest.importorskip("tqdm", reason="tqdm is not installed (Debian: python3-tqdm)")
    prtkit.bake(big, samples=64, progress=True)
    assert "bake" in capsys.readouterr().err


def test_threads_do_not_change_results(big):
    a = prtkit.bake(big, samples=64)
    prtkit.set_threads(1)
    try:
        assert prtkit.get_threads() == 1
        b = prtkit.bake(big, samples=64)
    finally:
        prtkit.set_threads(0)
    assert np.array_equal(a, b)
