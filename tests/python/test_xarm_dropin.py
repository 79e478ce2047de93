"""armctl.xarm, the drop-in for the xarm package: scripts in that package's style run
unchanged on the emulated xArm and on the SCARA arm controller, and the calls keep that
package's argument forms and return values (with its misbehaviours fixed)."""

import os
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

import armctl
import armctl.xarm as xarm
from conftest import script_env

SCRIPTS = Path(__file__).parent / "scripts"


def run_script(name, port):
    r = subprocess.run([sys.executable, str(SCRIPTS / name), port], env=script_env(), capture_output=True,
                       text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    return r.stdout


def test_servo_objects_map_angles_as_the_servos_turn():
    s = xarm.Servo(1, 300)
    assert (s.servo_id, s.position) == (1, 300)
    assert s.angle == pytest.approx(-48.0)  # 0.24 deg per unit
    s.angle = 90.0
    assert s.position == 875
    assert xarm.Servo(2, 120.0).position == 1000
    assert xarm.Servo(3).position == 500 and xarm.Servo(3).angle == 0.0
    with pytest.raises(ValueError):
        xarm.Servo(1, 125.0)  # that package's range; the servos turn 120 deg each way
    with pytest.raises(armctl.Error) as e:
        xarm.Servo(1, 1001)
    assert e.value.kind == "invalid_argument"


def test_calls_and_return_values_on_the_emulated_xarm():
    with xarm.Controller("sim", timeout=3.0) as arm:
        volts = arm.getBatteryVoltage()
        assert isinstance(volts, float) and 5.0 < volts < 13.0
        started = time.monotonic()
        p = arm.getPosition(1)
        assert time.monotonic() - started < 1.5  # not the full 3 s timeout per reply
        assert isinstance(p, int) and 0 <= p <= 1000
        arm.setPosition(1, 600, 300, wait=True)
        assert abs(arm.getPosition(1) - 600) <= 1
        arm.setPosition(2, -30.0, 300, wait=True)
        assert arm.getPosition(2, degrees=True) == pytest.approx(-30.0, abs=0.25)
        s1, s2 = xarm.Servo(1), xarm.Servo(2)
        assert arm.getPosition([s1, s2]) == [s1.position, s2.position]
        assert abs(s1.position - 600) <= 1
        assert arm.getPosition(s2, True) == pytest.approx(-30.0, abs=0.25)
        assert arm.listServos() == [1, 2, 3, 4, 5, 6]
        assert arm.listServos(2) == [1, 2]
        arm.servoOff()
        assert arm._present == [1, 2, 3, 4, 5, 6]


def test_argument_errors_are_value_errors_and_send_nothing():
    with xarm.Controller("sim") as arm:
        before = arm.getPosition(1)
        for bad in [lambda: arm.setPosition(1), lambda: arm.setPosition(1, 1200), lambda: arm.setPosition(1, 130.0),
                    lambda: arm.setPosition(1, 500, duration=40000), lambda: arm.setPosition("one", 500),
                    lambda: arm.setPosition([[1, 500], "two"]), lambda: arm.getPosition("x"),
                    lambda: arm.servoOff("all"), lambda: arm.writeServoId(0)]:
            with pytest.raises(ValueError) as e:
                bad()
            assert isinstance(e.value, armctl.Error) and e.value.kind == "invalid_argument"
        assert arm.getPosition(1) == before


def test_a_servo_that_does_not_answer_raises_a_timeout():
    with xarm.Controller("sim", timeout=0.2) as arm:
        with pytest.raises(armctl.Error) as e:
            arm.getPosition(7)
        assert e.value.kind == "timeout"


def test_windows_ports_are_explained():
    with pytest.raises(armctl.Error) as e:
        xarm.Controller("COM5")
    assert e.value.kind == "unsupported" and "/dev/tty" in e.value.message


@pytest.mark.parametrize("script", ["battery_and_positions.py", "move_servos.py", "servo_off.py"])
def test_scripts_run_on_the_emulated_xarm(script):
    out = run_script(script, "sim")
    assert out


def numbers(line):
    return [float(n) for n in re.findall(r"-?\d+(?:\.\d+)?", line.split(":", 1)[1])]


def test_move_script_positions(tmp_path):
    # wait=True returns once every servo is within one unit (0.24 deg) of its target, as
    # a real servo settles; the emulated one may still be that one unit short.
    out = run_script("move_servos.py", "sim").splitlines()
    assert out[0].startswith("servo 1:") and numbers(out[0]) == pytest.approx([300], abs=1)
    assert out[1].startswith("servo 2:") and numbers(out[1]) == pytest.approx([700], abs=1)
    assert out[2].startswith("servo 3 (degrees):") and numbers(out[2]) == pytest.approx([45.0], abs=0.25)
    assert out[-1].startswith("servos 1, 2, 3:") and numbers(out[-1]) == pytest.approx([500, 500, 500], abs=1)


@pytest.fixture
def arm_controller(tmp_path):
    """armctl's SCARA arm controller on a pty, as `armctl sim scara --robot-commands` serves it."""
    cli = os.environ.get("ARMCTL_CLI")
    if not cli or not os.path.exists(cli):
        pytest.skip("ARMCTL_CLI (the armctl binary) not set; CTest sets it")
    link = tmp_path / "scara"
    proc = subprocess.Popen([cli, "sim", "scara", "--robot-commands", "--link", str(link)],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        for _ in range(300):
            if link.exists() or proc.poll() is not None:
                break
            time.sleep(0.05)
        assert link.exists(), proc.stderr.read() if proc.poll() is not None else "no link"
        yield "serial:" + str(link)
    finally:
        proc.terminate()
        proc.wait(timeout=10)


def test_scripts_run_on_the_scara_arm_controller(arm_controller):
    out = run_script("battery_and_positions.py", arm_controller)
    assert "Servos: [1, 2, 3, 4, 5, 6]" in out
    out = run_script("servo_off.py", arm_controller)
    assert "off: [1, 2, 3, 4, 5, 6, 7]" in out  # all seven, not just 1..6


def test_com_ports_map_to_armctl_uris():
    uri = xarm._device_uri
    assert uri("USB", None) == "hid"
    assert uri("USB497223563535", None) == "hid:497223563535"
    assert uri("USB", "/dev/hidraw3") == "hid:/dev/hidraw3"
    assert uri("/dev/ttyUSB0", None) == "/dev/ttyUSB0"
    assert uri("serial:/dev/ttyAMA0?baud=115200", None) == "serial:/dev/ttyAMA0?baud=115200"
    with pytest.raises(ValueError):
        uri("", None)


def test_a_missing_usb_board_is_an_error_not_a_hang():
    started = time.monotonic()
    with pytest.raises(armctl.Error) as e:
        xarm.Controller("USB", usb_path="/dev/hidraw-none")
    assert e.value.kind in ("io", "invalid_argument")
    assert time.monotonic() - started < 5


def test_servo_ids_the_board_does_not_have_are_refused():
    with xarm.Controller("sim") as arm:  # the emulated xArm: six servos, though the drop-in assumes seven
        before = arm.getPosition(6)
        with pytest.raises(xarm.ArgumentError) as e:
            arm.setPosition(7, 500)
        assert e.value.kind == "invalid_argument"
        assert e.value.message == "servo ID 7 is not allowed: the board has servos 1, 2, 3, 4, 5, 6"
        with pytest.raises(xarm.ArgumentError):
            arm.setPosition([[6, 300], [7, 500]])  # refused whole: servo 6 does not move either
        assert arm.getPosition(6) == before
        arm.setPosition(6, before + 20, 100, wait=True)  # the servos it has still move
        assert abs(arm.getPosition(6) - (before + 20)) <= 1


def test_integral_numbers_of_any_type_are_accepted():
    import numpy as np

    with xarm.Controller("sim") as arm:
        arm.setPosition(np.int64(1), np.int64(600), np.int32(200), wait=True)
        assert abs(arm.getPosition(np.uint8(1)) - 600) <= 1
        arm.setPosition([[2, np.int16(400)], xarm.Servo(np.int64(3), np.int64(650))], 200.0, wait=True)
        assert [abs(p - t) <= 1 for p, t in zip(arm.getPosition([2, 3]), [400, 650])] == [True, True]
        arm.setPosition(4, np.float64(-30.0), 200, wait=True)  # a float, NumPy's too, is an angle
        assert arm.getPosition(4, degrees=True) == pytest.approx(-30.0, abs=0.25)
    s = xarm.Servo(1)
    s.position = np.int64(700)
    assert s.position == 700 and type(s.position) is int
    s.position = 650.0  # integral: units
    assert s.position == 650
    for bad in [True, np.bool_(True), 650.5, float("nan"), np.int64(1001), -1, "600"]:
        with pytest.raises(xarm.ArgumentError):
            s.position = bad
    for call in [lambda: xarm.Servo(True), lambda: xarm.Servo(np.int64(255)),
                 lambda: xarm.Controller.setPosition(None, 1, 500, duration=100.5),
                 lambda: xarm.Controller.setPosition(None, 1, 500, duration=True)]:
        with pytest.raises(xarm.ArgumentError):
            call()


def test_four_threads_move_one_arm():
    import threading

    with xarm.Controller("sim") as arm:  # the link's own reply timeout, 0.5 s
        start = threading.Barrier(4)
        raised = []
        targets = {1: [300, 700], 2: [350, 650], 3: [400, 600], 4: [450, 550]}

        def moves(sid):
            try:
                start.wait(30)
                for position in targets[sid]:
                    arm.setPosition(sid, position, 100, wait=True)
                    assert abs(arm.getPosition(sid) - position) <= 1
            except BaseException as e:  # noqa: B036 (reported below)
                raised.append(e)

        threads = [threading.Thread(target=moves, args=(sid,)) for sid in targets]
        for t in threads:
            t.start()
        for t in threads:
            t.join(60)
            assert not t.is_alive()
        assert raised == []
        assert [abs(p - t[-1]) <= 1 for p, t in zip(arm.getPosition(list(targets)), targets.values())] == [True] * 4
