"""The servo mode from Python (docs/servo.md): arm.servo() as a with block follows twists and
joint targets as they are sent, comes to rest when they stop and at the block's end (also on
an exception), refuses bad commands, and keeps the arm's other calls out while it runs."""

import math
import time

import pytest

import armctl


def bent(arm):
    """Away from the upright start (a singularity): the elbow bent, the tool in front."""
    arm.move_joints([0.0, 0.5, 1.0, 1.0, 0.0, None], wait=True)
    return arm.pose().position.copy()


def hold(seconds, send):
    """Sends a command every 20 ms for `seconds` (as a stick or a held key renews it)."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        send()
        time.sleep(0.02)


def test_a_twist_moves_the_tool_and_the_block_end_brings_it_to_rest(xarm):
    before = bent(xarm)
    with xarm.servo() as s:
        hold(1.0, lambda: s.twist(linear=[0, 0.02, 0]))
    moved = (xarm.wait().positions, xarm.pose().position - before)[1] * 1000
    # 20 mm/s for about a second (the host's timing is not exact).
    assert 12 < moved[1] < 30
    assert abs(moved[0]) < 1.5 and abs(moved[2]) < 1.5


def test_commands_that_stop_coming_bring_the_arm_to_rest(xarm):
    bent(xarm)
    with xarm.servo(timeout=0.2) as s:
        s.twist(linear=[0, 0, -0.02])
        time.sleep(1.0)  # a script that stopped sending: the timeout stops the arm
        status = s.status
    assert status["at_rest"]
    assert status["slowdown"] == "command timeout"


def test_joint_targets_are_reached_and_the_gripper_goes_with_them(xarm):
    q = xarm.read().positions.copy()
    q[0] = 0.3
    with xarm.servo() as s:
        hold(1.5, lambda: s.joint_targets([q[0], q[1], q[2], q[3], q[4], None]))
        s.gripper(1.0)
        time.sleep(0.8)
    now = xarm.wait().positions
    assert math.isclose(now[0], 0.3, abs_tol=0.01)


def test_bad_commands_raise_and_the_session_goes_on(xarm):
    with xarm.servo() as s:
        with pytest.raises(armctl.Error) as e:
            s.twist(linear=[math.nan, 0, 0])
        assert "finite" in str(e.value)
        with pytest.raises(armctl.Error, match="'base' or 'tool'"):
            s.twist(linear=[0.01, 0, 0], frame="world")
        with pytest.raises(armctl.Error, match="6 joints"):
            s.joint_velocities([0.1, 0.2])
        with pytest.raises(armctl.Error, match="0 \\(open\\) to 1 \\(closed\\)"):
            s.gripper(2)
        s.stop()
    with pytest.raises(armctl.Error, match="speed"):
        xarm.servo(speed=0)


def test_the_arms_calls_wait_for_the_session_and_an_exception_ends_it_at_rest(xarm):
    bent(xarm)
    with pytest.raises(RuntimeError, match="the script failed"):
        with xarm.servo() as s:
            with pytest.raises(armctl.Error, match="servo session"):
                xarm.pose()
            hold(0.3, lambda: s.twist(linear=[0.02, 0, 0]))
            raise RuntimeError("the script failed")
    # The session ended at rest, and the arm answers again.
    first = xarm.read().positions.copy()
    time.sleep(0.2)
    assert max(abs(a - b) for a, b in zip(first, xarm.read().positions)) < 0.01
    with pytest.raises(armctl.Error, match="not running"):
        s.twist(linear=[0.01, 0, 0])
