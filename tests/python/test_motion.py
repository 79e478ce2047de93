"""Host-planned motion from Python: the jerk-limited joint move, LIN and CIRC paths with
zones, streamed through the executor to the embedded simulators."""

import math

import numpy as np
import pytest

import armctl

DEG = math.pi / 180


def test_joint_move_through_a_waypoint(xarm):
    report = xarm.joint_move({"servo6": 10 * DEG}, waypoints=[{"servo6": 5 * DEG, "servo5": 3 * DEG}], speed=0.5)
    assert isinstance(report, armctl.MotionReport)
    assert report.completed and not report.stopped
    assert report.points > 3 and report.duration > 0
    s = xarm.read()
    assert s.positions[0] == pytest.approx(10 * DEG, abs=0.3 * DEG)
    assert s.positions[1] == pytest.approx(0.0, abs=0.3 * DEG)


def test_move_linear_keeps_the_tool_on_the_line(xarm):
    xarm.move_to([0.16, 0.0, 0.12], pitch=50 * DEG, duration=0.6, wait=True)
    start = xarm.pose().position
    report = xarm.move_linear([0.16, 0.03, 0.12], speed=0.06)
    assert report.completed
    end = xarm.pose().position
    assert np.allclose(end, [0.16, 0.03, 0.12], atol=0.004)
    assert report.largest_following_error < 5 * DEG
    assert isinstance(report.held, float) and 0.0 <= report.held < report.elapsed
    assert np.linalg.norm(end - start) > 0.025


def test_path_of_lin_and_circ_with_a_zone(xarm):
    xarm.move_to([0.16, 0.0, 0.12], pitch=50 * DEG, duration=0.6, wait=True)
    segments = [
        armctl.Lin([0.16, 0.02, 0.12], speed=0.06, zone=0.005),
        armctl.Circ(via=[0.15, 0.03, 0.12], position=[0.14, 0.02, 0.12], speed=0.06),
    ]
    assert segments[0].kind == "LIN" and segments[1].kind == "CIRC"
    report = xarm.path(segments)
    assert report.completed
    assert np.allclose(xarm.pose().position, [0.14, 0.02, 0.12], atol=0.004)


def test_scara_line_on_the_joint_bus(scara):
    scara.move_joints({"UAE": 40 * DEG}, duration=1.0, wait=True)  # out of the stretched pose
    here = scara.pose()
    goal = here.position + np.array([0.0, 0.02, 0.0])
    report = scara.move_linear(goal, speed=0.05)
    assert report.completed
    assert np.allclose(scara.pose().position, goal, atol=0.002)


def test_motion_refusals(xarm):
    before = xarm.read().device
    with pytest.raises(armctl.Error) as e:
        xarm.path([])
    assert e.value.kind == "invalid_argument"
    with pytest.raises(armctl.Error) as e:
        xarm.move_linear([0.6, 0.0, 0.1])
    assert e.value.kind == "invalid_argument"
    with pytest.raises(armctl.Error) as e:
        xarm.joint_move({"servo6": 3.0})
    assert e.value.kind == "invalid_argument" and "servo6" in e.value.message
    with pytest.raises(armctl.Error) as e:
        xarm.joint_move({"servo6": 0.1}, speed_override=0)
    assert e.value.kind == "invalid_argument"
    with pytest.raises(armctl.Error) as e:
        armctl.Lin([0.1, 0.2])
    assert e.value.kind == "invalid_argument"
    with pytest.raises(armctl.Error) as e:
        xarm.path([armctl.Lin([0.16, 0.02, 0.12], speed=-1)])
    assert e.value.kind == "invalid_argument"
    assert np.array_equal(xarm.read().device, before)


def test_extreme_targets_speeds_and_durations(xarm):
    """1e200 crashed the planner (heap-buffer-overflow); 1e-300 speeds were accepted; a
    duration of 0.1 s moved servo6 at twice its arm file's 180 deg/s."""
    before = xarm.read().device
    for x in (1e200, 1e305):
        with pytest.raises(armctl.Error) as e:
            xarm.move_linear([x, 0.0, 0.1])
        assert e.value.kind == "invalid_argument" and "is beyond reach: arm 'xarm' reaches at most" in e.value.message
        with pytest.raises(armctl.Error) as e:
            xarm.path([armctl.Lin([0.16, x, 0.12])])
        assert "y " in e.value.message and "is beyond reach" in e.value.message
    with pytest.raises(armctl.Error) as e:
        xarm.move_linear([0.16, 0.02, 0.12], speed=1e-300)
    assert "speed: 1e-300 m/s is too slow; allowed 0.1..500 mm/s" in e.value.message
    with pytest.raises(armctl.Error) as e:
        xarm.joint_move({"servo6": 0.1}, speed_override=1e-300)
    assert "speed_override: 1e-300 is too small; allowed 0.001..1 (0.1..100 %)" in e.value.message
    assert np.array_equal(xarm.read().device, before)
    xarm.move_joints({"servo6": -1.7}, speed=1.0, wait=True)
    with pytest.warns(UserWarning, match="duration=0.1 is too short for joint servo6 to move 194.8"):
        xarm.move_joints({"servo6": 1.7}, duration=0.1, wait=True)
