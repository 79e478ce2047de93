"""Ctrl-C (SIGINT: KeyboardInterrupt) during a move or a wait stops the arm short of its
target, then raises KeyboardInterrupt; the waits release the GIL meanwhile."""

import math
import os
import signal
import threading
import time

import pytest

DEG = math.pi / 180


def interrupt_after(seconds):
    timer = threading.Timer(seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    return timer


def test_ctrl_c_during_a_streamed_move_stops_on_the_way(xarm):
    timer = interrupt_after(0.5)
    started = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        xarm.joint_move({"servo6": 90 * DEG}, speed=0.2)  # about 2.5 s
    timer.join()
    assert time.monotonic() - started < 2.0
    first = xarm.read().positions[0]
    time.sleep(0.3)
    second = xarm.read().positions[0]
    assert 2 * DEG < first < 60 * DEG  # it moved, and stopped well short
    assert abs(second - first) < 0.5 * DEG  # at rest


def test_ctrl_c_during_a_wait_stops_the_device_move(xarm):
    xarm.move_joints({"servo6": -60 * DEG}, duration=3.0)
    timer = interrupt_after(0.5)
    with pytest.raises(KeyboardInterrupt):
        xarm.wait(timeout=10)
    timer.join()
    first = xarm.read().positions[0]
    time.sleep(0.3)
    assert -40 * DEG < first < -1 * DEG
    assert abs(xarm.read().positions[0] - first) < 0.5 * DEG


def test_ctrl_c_during_a_line(xarm):
    xarm.move_to([0.16, -0.04, 0.12], pitch=50 * DEG, duration=0.5, wait=True)
    timer = interrupt_after(0.4)
    with pytest.raises(KeyboardInterrupt):
        xarm.move_linear([0.16, 0.04, 0.12], speed=0.03)  # about 2.7 s
    timer.join()
    y = xarm.pose().position[1]
    assert -0.04 < y < 0.03


def test_other_threads_run_during_a_wait(xarm):
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.01)

    t = threading.Thread(target=count)
    t.start()
    xarm.move_joints({"servo6": 5 * DEG}, duration=0.5, wait=True)
    stop.set()
    t.join()
    assert len(ticks) > 20  # the GIL was free while the arm moved
