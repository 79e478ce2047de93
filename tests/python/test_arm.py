"""armctl.Arm against the embedded simulators: reading, kinematics, device moves, and every
refusal raising armctl.Error with its kind, before anything moves."""

import math
from pathlib import Path

import numpy as np
import pytest

import armctl

DEG = math.pi / 180


def test_model_of_the_xarm(xarm):
    assert xarm.name == "xarm"
    assert xarm.joint_names == ["servo6", "servo5", "servo4", "servo3", "servo2", "servo1"]
    assert xarm.chain_joints == 5
    assert xarm.protocol == "robot_commands"
    j = xarm.joints[0]
    assert (j.kind, j.role, j.robot_commands_id, j.joint_bus_id) == ("revolute", "chain", 6, None)
    assert j.lower == pytest.approx(-120 * DEG) and j.upper == pytest.approx(120 * DEG)
    assert j.velocity == pytest.approx(180 * DEG)
    assert xarm.joints[-1].role == "gripper"


def test_read_gives_numpy_arrays_in_si_and_device_units(xarm):
    s = xarm.read()
    assert isinstance(s.positions, np.ndarray) and s.positions.shape == (6,)
    assert isinstance(s.device, np.ndarray) and s.device.shape == (6,)
    # 500 is the centre of every servo: 0 rad
    for si, dev in zip(s.positions, s.device):
        assert si == pytest.approx((dev - 500) * 0.24 * DEG, abs=1e-9)
    assert s.time > 0


def test_pose_is_forward_of_read(xarm):
    s = xarm.read()
    p = xarm.pose()
    f = xarm.forward(s.positions)
    assert np.allclose(p.position, f.position)
    assert f.orientation.shape == (4,)
    assert np.linalg.norm(f.orientation) == pytest.approx(1.0)
    assert np.allclose(xarm.forward(s.positions[:5]).position, f.position)


def test_inverse_then_forward_reaches_the_point(xarm):
    target = [0.15, 0.05, 0.12]
    solutions = xarm.inverse(target)
    assert solutions
    p = xarm.forward(solutions[0].joints)
    assert np.allclose(p.position, target, atol=1e-6)
    assert p.yaw == pytest.approx(math.atan2(0.05, 0.15), abs=1e-6)


def test_move_joints_arrives_and_wait_returns_the_state(xarm):
    xarm.move_joints({"servo6": 10 * DEG, 1: -5 * DEG}, duration=0.4, wait=True)
    s = xarm.read()
    assert s.positions[0] == pytest.approx(10 * DEG, abs=0.3 * DEG)
    assert s.positions[1] == pytest.approx(-5 * DEG, abs=0.3 * DEG)
    xarm.move_joints([0.0, None, None, None, None, None], duration=0.3)
    s = xarm.wait(timeout=5)
    assert s.positions[0] == pytest.approx(0, abs=0.3 * DEG)
    assert s.positions[1] == pytest.approx(-5 * DEG, abs=0.3 * DEG)


def test_move_to_puts_the_tool_there(xarm):
    xarm.move_to([0.15, 0.05, 0.12], duration=0.5, wait=True)
    assert np.allclose(xarm.pose().position, [0.15, 0.05, 0.12], atol=0.003)


def test_gripper_torque_and_stop(xarm):
    g = xarm.joints[-1]
    xarm.gripper(1.0, duration=0.3, wait=True)
    closed = xarm.read().positions[-1]
    xarm.gripper(0.0, duration=0.3, wait=True)
    opened = xarm.read().positions[-1]
    assert abs(closed - opened) > 10 * DEG
    assert g.lower - 1e-9 <= closed <= g.upper + 1e-9
    xarm.set_torque(False)
    xarm.set_torque(True)
    xarm.move_joints({"servo6": 30 * DEG}, duration=2.0)
    xarm.stop()
    still = xarm.read().positions[0]
    assert still < 25 * DEG  # stopped well short of the target
    xarm.wait(timeout=2)  # nothing left to wait for after a stop


def test_health_and_clearing_faults_on_both_arms(xarm, scara):
    h = xarm.health()
    assert h["battery_volts"] > 6.0
    assert h["faults"] == []
    xarm.clear_faults()  # the emulated xArm holds none: nothing to clear, no error
    s = scara.health()
    assert s["battery_volts"] is None  # nothing measures the supply on the joint bus
    assert s["faults"] == []
    scara.clear_faults()  # each joint answers clear_faults on the bus


def test_the_scara_on_its_joint_bus(scara):
    assert scara.protocol == "joint_bus"
    assert scara.chain_joints == 6
    z = scara.joints[0]
    assert z.kind == "prismatic" and z.joint_bus_id is not None
    before = scara.read().positions
    target = [None] * len(before)
    target[1] = before[1] + 5 * DEG
    scara.move_joints(target, duration=1.0, wait=True, timeout=10)
    assert scara.read().positions[1] == pytest.approx(before[1] + 5 * DEG, abs=0.6 * DEG)


def error_of(call, *args, **kwargs):
    with pytest.raises(armctl.Error) as e:
        call(*args, **kwargs)
    assert isinstance(e.value, RuntimeError)
    assert str(e.value) == e.value.message
    return e.value


def test_refusals_name_what_was_wrong_and_send_nothing(xarm):
    before = xarm.read().device
    e = error_of(xarm.move_joints, {"servo6": 130 * DEG}, duration=0.2)
    assert e.kind == "invalid_argument" and "servo6" in e.message
    e = error_of(xarm.move_joints, [0.0] * 3)
    assert e.kind == "invalid_argument" and "6 joints" in e.message
    e = error_of(xarm.move_joints, {"elbow": 0.1})
    assert e.kind == "invalid_argument" and "no joint 'elbow'" in e.message
    e = error_of(xarm.move_joints, {"servo6": float("nan")})
    assert e.kind == "invalid_argument"
    e = error_of(xarm.move_joints, {"servo6": 0.1}, speed=1.5)
    assert e.kind == "invalid_argument"
    e = error_of(xarm.move_joints, {"servo6": 0.1}, duration=-1)
    assert e.kind == "invalid_argument"
    e = error_of(xarm.move_to, [1.0, 0.0, 0.1])
    assert e.kind == "invalid_argument" and "beyond reach" in e.message
    e = error_of(xarm.move_to, [0.1, 0.0])
    assert e.kind == "invalid_argument"
    e = error_of(xarm.inverse, [0.15, 0.0, 0.1], elbow="sideways")
    assert e.kind == "invalid_argument" and "elbow" in e.message
    e = error_of(xarm.forward, [0.0, 0.0])
    assert e.kind == "invalid_argument"
    e = error_of(xarm.gripper, 2.0)
    assert e.kind == "invalid_argument"
    assert np.array_equal(xarm.read().device, before)  # nothing moved


@pytest.mark.parametrize("arm_name", ["xarm", "scara"])
def test_forward_refuses_joints_that_are_not_finite_or_past_a_limit(arm_name):
    with armctl.Arm(arm_name) as arm:
        chain = arm.joints[:arm.chain_joints]
        inside = [(j.lower + j.upper) / 2 for j in chain]
        arm.forward(inside)  # the middle of every range: a pose
        for i, j in enumerate(chain):
            unit = "rad" if j.kind == "revolute" else "m"
            for bad, shown in [(1e308, "1e+308"), (float("inf"), "inf"), (float("nan"), "nan"),
                               (j.upper + 0.01, f"{j.upper + 0.01:g}"), (j.lower - 0.01, f"{j.lower - 0.01:g}")]:
                q = list(inside)
                q[i] = bad
                e = error_of(arm.forward, q)
                assert e.kind == "invalid_argument"
                assert e.message == f"joint {j.name}: {shown} {unit} is not allowed: {j.lower:.4f}..{j.upper:.4f} {unit}"
        # Every joint given: the gripper is ignored, whatever it says.
        assert arm.forward(inside + [1e308] * (len(arm.joints) - len(chain))) is not None


def test_wait_timeout_names_the_late_joint(xarm):
    xarm.move_joints({"servo6": 20 * DEG}, duration=1.5)
    e = error_of(xarm.wait, timeout=0.2)
    assert e.kind == "timeout" and "servo6" in e.message
    xarm.stop()


def test_bad_devices_and_closed_arms():
    e = error_of(armctl.Arm, "xarm", "carrier-pigeon:x")
    assert e.kind == "invalid_argument"
    e = error_of(armctl.Arm, "no-such-arm")
    assert e.kind in ("invalid_config", "io")
    arm = armctl.Arm()
    arm.close()
    e = error_of(arm.read)
    assert e.kind == "invalid_argument" and "closed" in e.message


def test_action_groups_need_robot_commands(scara):
    e = error_of(scara.run_group, 1)
    assert e.kind == "unsupported"


def test_action_groups_on_the_emulated_xarm(xarm):
    xarm.download_group(3, "servos 2\n200 1=520 2=480\n200 1=500 2=500\n")
    xarm.run_group(3, 1)
    events = xarm.group_events(timeout=2.0)
    while not any(ev["kind"] == "finished" for ev in events):
        more = xarm.group_events(timeout=2.0)
        assert more, "no group notification in 2 s"
        events += more
    assert events[0] == {"kind": "started", "group": 3, "count": 1}
    e = error_of(xarm.download_group, 3, "servos 2\n200 1=5000 2=480\n")
    assert e.kind == "invalid_config" or e.kind == "invalid_argument"
    e = error_of(xarm.run_group, 300)
    assert e.kind == "invalid_argument"
    xarm.erase_group(3)
    xarm.stop_group()


def test_a_program_goes_around_the_box_with_avoid(tmp_path):
    # The same move as a program line: refused naming the line and the box, run with avoid.
    scene = str(Path(__file__).resolve().parents[2] / "examples" / "scenes" / "xarm-desk.json")
    program = tmp_path / "behind.prog"
    program.write_text("wait 0.1s\nptp pose(x=150mm, y=-190mm, z=40mm)\n")
    with armctl.Arm(scene=scene) as arm:
        with pytest.raises(armctl.Error, match=r"behind.prog:2.*box 'box'") as refused:
            arm.check_program(str(program))
        # The collision's detail, at the program's line.
        assert refused.value.detail == "collision"
        assert "box 'box'" in refused.value.bodies
        assert (refused.value.file, refused.value.line) == (str(program), 2)
        assert refused.value.while_moving is False
        assert arm.check_program(str(program), avoid=True)["duration"] > 0.1
        with pytest.raises(armctl.Error, match="avoid_time"):
            arm.run_program(str(program), avoid=True, avoid_time=0)
        report = arm.run_program(str(program), avoid=True, avoid_time=5)
        assert report["completed"]
        assert np.allclose(arm.pose().position, [0.15, -0.19, 0.04], atol=0.003)


def test_move_to_avoid_goes_around_the_box():
    # The README's scene: behind the box the direct move swings the wrist through it.
    scene = str(Path(__file__).resolve().parents[2] / "examples" / "scenes" / "xarm-desk.json")
    with armctl.Arm(scene=scene) as arm:
        with pytest.raises(armctl.Error, match="with box 'box'"):
            arm.move_to([0.15, -0.19, 0.04])
        planned = arm.move_to([0.15, -0.19, 0.04], avoid=True, wait=True)
        assert planned.duration > 0
        assert np.allclose(arm.pose().position, [0.15, -0.19, 0.04], atol=0.003)
        with pytest.raises(armctl.Error, match="avoid_time"):
            arm.move_to([0.15, -0.19, 0.04], avoid=True, avoid_time=0)
