"""One armctl.Arm (or RobotCommands connection) used from several Python threads: calls take
turns on the device, and close() from one thread stops what another runs (a wait ends, a
streamed motion stops on its path), waits for it, then ends the device. No call crashes, hangs
or sees another thread's reply. Every wait here is on a condition, with a deadline."""

import math
import os
import subprocess
import sys
import threading
import time

import pytest

import armctl
from conftest import script_env

DEG = math.pi / 180
DEADLINE = 30  # s: far beyond what any of these takes; reached only when something hangs


def run_threads(count, body):
    """Runs body(i) on `count` threads started together; returns what each raised (None: nothing)."""
    start = threading.Barrier(count)
    raised = [None] * count

    def run(i):
        try:
            start.wait(DEADLINE)
            body(i)
        except BaseException as e:  # noqa: B036 (reported to the test)
            raised[i] = e

    threads = [threading.Thread(target=run, args=(i,)) for i in range(count)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(DEADLINE)
        assert not t.is_alive(), "a thread hangs"
    return raised


class Marker:
    """A joint value whose conversion (done while the call has its turn on the arm) says so:
    the test then knows that the call runs before it closes the arm."""

    def __init__(self, value, inside):
        self.value, self.inside = float(value), inside

    def __float__(self):
        self.inside.set()
        return self.value


@pytest.mark.parametrize("arm_name", ["xarm", "scara"])
def test_eight_threads_read_one_arm(arm_name):
    with armctl.Arm(arm_name) as arm:
        joints = len(arm.joint_names)
        expected = arm.read().positions
        states = [[] for _ in range(8)]

        def reads(i):
            for _ in range(5):
                states[i].append(arm.read())

        assert run_threads(8, reads) == [None] * 8
        for s in (s for per_thread in states for s in per_thread):
            assert s.positions.shape == (joints,) and s.device.shape == (joints,)
            assert s.positions == pytest.approx(expected, abs=0.01)  # nothing moves: every read agrees


READ_BEFORE_NUMPY = """
import sys, threading
import armctl  # this script itself never imports numpy before its threads read
arms = [armctl.Arm(), armctl.Arm()]
start = threading.Barrier(9)
failed = []
def reads(arm):
    try:
        start.wait(30)
        for _ in range(3):
            assert len(arm.read().positions) == 6
    except BaseException as e:
        failed.append(repr(e))
def imports():
    start.wait(30)
    import numpy
threads = [threading.Thread(target=reads, args=(arms[i % 2],)) for i in range(8)]
threads.append(threading.Thread(target=imports))
for t in threads: t.start()
for t in threads: t.join()
print("failed:", failed)
sys.exit(1 if failed else 0)
"""


def test_threads_whose_first_read_comes_before_numpy_is_imported():
    # A child process, so that NumPy is not already imported: four threads on each of two
    # arms take their first NumPy results while a ninth imports numpy. Hung: the timeout.
    r = subprocess.run([sys.executable, "-c", READ_BEFORE_NUMPY], env=script_env(), capture_output=True, text=True,
                       timeout=60)
    assert r.returncode == 0, r.stdout + r.stderr


def test_close_while_other_threads_read():
    arm = armctl.Arm()
    read_once = threading.Barrier(9)  # eight readers and this test: each has read at least once

    def reads(i):
        arm.read()
        read_once.wait(DEADLINE)
        while True:
            arm.read()  # until close() ends it: armctl.Error

    raised = []
    threads = [threading.Thread(target=lambda i=i: raised.append(capture(reads, i))) for i in range(8)]
    for t in threads:
        t.start()
    read_once.wait(DEADLINE)
    arm.close()
    for t in threads:
        t.join(DEADLINE)
        assert not t.is_alive()
    assert len(raised) == 8
    for e in raised:
        assert isinstance(e, armctl.Error) and e.kind == "invalid_argument" and "closed" in e.message, e


def capture(body, *args, **kwargs):
    """What body(*args, **kwargs) raised, or None."""
    try:
        body(*args, **kwargs)
    except BaseException as e:  # noqa: B036 (reported to the test)
        return e
    return None


def start_long_wait(arm):
    """Another thread's 20 s device move and its wait, under way: (start, raised, thread)."""
    start = arm.read().positions[0]
    inside = threading.Event()
    raised = []
    mover = threading.Thread(target=lambda: raised.append(capture(
        arm.move_joints, {"servo6": Marker(start + 80 * DEG, inside)}, duration=20, wait=True, timeout=DEADLINE)))
    mover.start()
    assert inside.wait(DEADLINE)
    return start, raised, mover


def test_close_while_another_thread_waits_stops_the_arm(xarm_on_a_link):
    device, reopen = xarm_on_a_link
    arm = armctl.Arm("xarm", device)
    # close() must not wait for the move's 20 s.
    start, raised, mover = start_long_wait(arm)
    began = time.monotonic()
    arm.close()
    took = time.monotonic() - began
    mover.join(DEADLINE)
    assert took < 5
    e = raised[0]
    assert isinstance(e, armctl.Error) and "closed during a wait" in e.message, e
    with reopen() as again:  # the board kept running: the arm stands where it was stopped
        assert_at_rest_short_of(again, start, start + 80 * DEG)


def test_close_while_another_thread_streams_stops_on_the_path(xarm_on_a_link):
    device, reopen = xarm_on_a_link
    arm = armctl.Arm("xarm", device)
    start = arm.read().positions[0]
    inside = threading.Event()
    raised = []
    target = start - 90 * DEG
    mover = threading.Thread(target=lambda: raised.append(capture(
        arm.joint_move, {"servo6": Marker(target, inside)}, speed=0.1)))  # about 5 s
    mover.start()
    assert inside.wait(DEADLINE)
    began = time.monotonic()
    arm.close()
    took = time.monotonic() - began
    mover.join(DEADLINE)
    assert took < 4
    e = raised[0]
    assert isinstance(e, armctl.Error) and "closed during a streamed motion" in e.message, e
    with reopen() as again:
        assert_at_rest_short_of(again, start, target)


def assert_at_rest_short_of(arm, start, target):
    """The base joint stands still between start (inclusive) and target, not at the target."""
    first = arm.read().positions[0]
    lo, hi = sorted((start, target))
    assert lo - DEG <= first <= hi + DEG and abs(first - target) > 5 * DEG
    # At rest: a moving base (at least 4 deg/s on these moves) would move a unit in 60 ms.
    until = time.monotonic() + 0.5
    while time.monotonic() < until:
        assert abs(arm.read().positions[0] - first) < 0.6 * DEG


def test_close_while_another_thread_waits_for_group_events():
    rc = armctl.RobotCommands()
    raised = []
    listener = threading.Thread(target=lambda: raised.append(capture(rc.group_events, 3600)))
    listener.start()
    began = time.monotonic()
    rc.close()  # between two of the listener's turns: not after the hour
    listener.join(DEADLINE)
    assert not listener.is_alive() and time.monotonic() - began < 5
    assert isinstance(raised[0], armctl.Error) and "closed" in raised[0].message, raised[0]


def test_a_thread_listening_for_group_events_lets_other_calls_through():
    with armctl.RobotCommands() as rc:
        rc.download_group(2, "servos 1\n100 1=510\n")
        events = []
        listening = threading.Event()

        def listen():
            until = time.monotonic() + DEADLINE
            while "finished" not in [e["kind"] for e in events] and time.monotonic() < until:
                listening.set()
                events.extend(rc.group_events(0.5))

        listener = threading.Thread(target=listen)
        listener.start()
        assert listening.wait(DEADLINE)
        # Each call goes between two of the listener's short turns (50 ms), not after its 0.5 s.
        longest = 0
        for _ in range(5):
            began = time.monotonic()
            rc.battery_millivolts()
            longest = max(longest, time.monotonic() - began)
        rc.run_group(2, 1)
        listener.join(DEADLINE)
        assert [e["kind"] for e in events] == ["started", "finished"]
        assert longest < 0.3


def test_stop_from_another_thread_ends_a_wait_without_waiting_for_it():
    with armctl.Arm() as arm:
        start, raised, mover = start_long_wait(arm)
        began = time.monotonic()
        arm.stop()
        assert time.monotonic() - began < 3  # not the move's 20 s
        mover.join(DEADLINE)
        e = raised[0]
        assert isinstance(e, armctl.Error) and "stop() was called" in e.message, e
        assert_at_rest_short_of(arm, start, start + 80 * DEG)


def test_stop_from_another_thread_stops_a_streamed_motion_on_its_path():
    with armctl.Arm() as arm:
        start = arm.read().positions[0]
        target = start - 90 * DEG
        inside = threading.Event()
        reports = []
        mover = threading.Thread(target=lambda: reports.append(arm.joint_move({"servo6": Marker(target, inside)},
                                                                              speed=0.1)))
        mover.start()
        assert inside.wait(DEADLINE)
        arm.stop()
        mover.join(DEADLINE)
        assert reports[0].stopped and not reports[0].completed
        assert_at_rest_short_of(arm, start, target)


def test_calls_after_close_are_refused_and_a_second_close_is_harmless():
    arm = armctl.Arm()
    arm.close()
    arm.close()
    with pytest.raises(armctl.Error) as e:
        arm.joint_names
    assert e.value.kind == "invalid_argument" and "closed" in e.value.message


@pytest.fixture
def xarm_on_a_link(tmp_path):
    """An emulated xArm in its own process (`armctl sim xarm --link`), so that what an arm
    closed in this one left it doing can be read afterwards: (device URI, reopen())."""
    cli = os.environ.get("ARMCTL_CLI")
    if not cli or not os.path.exists(cli):
        pytest.skip("ARMCTL_CLI (the armctl binary) not set; CTest sets it")
    link = tmp_path / "xarm"
    proc = subprocess.Popen([cli, "sim", "xarm", "--link", str(link), "--state-dir", str(tmp_path / "board")],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        until = time.monotonic() + DEADLINE
        while not link.exists() and proc.poll() is None and time.monotonic() < until:
            time.sleep(0.02)  # polls for the link to appear
        assert link.exists(), proc.stderr.read() if proc.poll() is not None else "no link"
        device = "serial:" + str(link)
        yield device, lambda: armctl.Arm("xarm", device)
    finally:
        proc.terminate()
        proc.wait(timeout=10)
