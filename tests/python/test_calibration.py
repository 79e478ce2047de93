"""armctl.Calibration (docs/calibration.md "Python"): the wizard's steps on the embedded SCARA
simulator with an arm file of the test's own, answered as a user would: the joint went the
other way than the picture shows, and it stands at its mark. Confirm writes the file (the old
one kept beside it) and the Arm drives with it from then on; a block left without confirm writes
nothing."""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import armctl
from conftest import script_env

CONFIG = Path(os.environ.get("ARMCTL_CONFIG_DIR", Path(__file__).resolve().parents[2] / "config"))
JOINT = "UAE"  # a revolute chain joint of the SCARA


def copy_of_shipped_arm(tmp_path, family):
    """The shipped arm file of `family` and its URDF, copied into a folder of the test's own."""
    folder = tmp_path / family
    folder.mkdir()
    for name in (f"{family}.arm.json", f"{family}.urdf"):
        shutil.copy(CONFIG / name, folder / name)
    return folder / f"{family}.arm.json"


@pytest.fixture
def arm_file(tmp_path):
    return copy_of_shipped_arm(tmp_path, "scara")


def test_direction_and_zero_are_written_on_confirm_with_the_previous_file_kept(arm_file):
    original = arm_file.read_bytes()
    with armctl.Arm(str(arm_file)) as arm:
        j = arm.joint_names.index(JOINT)
        before = arm.read().positions[j]
        with arm.calibration() as cal:
            cal.nudge(JOINT)
            after = arm.read().positions[j]
            assert after > before + 0.05  # it went positive, as the arm file has it
            cal.answer_direction(JOINT, False)  # the user saw it go the other way
            zero = cal.zero_here(j, 0.0)  # by index; it stands at its mark now
            assert zero["kind"] == "file_zero"
            changes = cal.changes()
            assert [c["joint"] for c in changes["joints"]] == [JOINT]
            assert changes["joints"][0]["flip"] is True
            # new = -old + shift reads 0 here
            assert changes["joints"][0]["zero_shift"] == pytest.approx(after, abs=1e-3)
            assert JOINT in cal.describe() and "flipped" in cal.describe()
            assert arm_file.read_bytes() == original  # nothing written before confirm
            written = cal.confirm()
            with pytest.raises(armctl.Error):
                cal.describe()  # confirm ends the session
        # The Arm drives with the new file at once: the joint, where it stands, reads its
        # mark, and a second calibration starts from the new file.
        assert arm.read().positions[j] == pytest.approx(0.0, abs=2e-3)
        with arm.calibration() as cal:
            assert cal.changes()["empty"]
        assert Path(written["file"]) == arm_file
        assert Path(written["previous"]).read_bytes() == original
        assert arm_file.read_bytes() != original
    # A fresh simulator stands where the first one started: the new file reads it flipped
    # about the mark.
    with armctl.Arm(str(arm_file)) as arm:
        assert arm.read().positions[j] == pytest.approx(after - before, abs=2e-3)


def test_a_block_left_without_confirm_writes_nothing(arm_file):
    original = arm_file.read_bytes()
    with armctl.Arm(str(arm_file)) as arm:
        with pytest.raises(KeyError):
            with arm.calibration() as cal:
                cal.answer_direction(JOINT, False)
                cal.zero_here(JOINT)
                assert not cal.changes()["empty"]
                raise KeyError("the user walked away")
        for call in (cal.describe, lambda: cal.nudge(JOINT), cal.verify):  # the session ended with its block
            with pytest.raises(armctl.Error) as e:
                call()
            assert e.value.kind == "invalid_argument"
    assert arm_file.read_bytes() == original
    assert sorted(p.name for p in arm_file.parent.iterdir()) == ["scara.arm.json", "scara.urdf"]  # no .prev


def test_wrong_values_raise_armctl_error_naming_what_is_allowed(arm_file):
    with armctl.Arm(str(arm_file)) as arm, arm.calibration() as cal:
        for call in (lambda: cal.nudge("nope"), lambda: cal.wiggle(99), lambda: cal.touch("p", [0.1, 0.2]),
                     lambda: cal.verify()):
            with pytest.raises(armctl.Error) as e:
                call()
            assert e.value.kind == "invalid_argument"
        with pytest.raises(armctl.Error) as e:
            cal.nudge("nope")
        assert "UAE" in str(e.value)  # the allowed names
        # A mix-up in "which joint is which" is an error naming both joints.
        cal.answer_which(JOINT, JOINT)
        with pytest.raises(armctl.Error) as e:
            cal.answer_which(JOINT, "UAJ")
        assert "UAJ" in str(e.value)
        assert cal.changes()["empty"]
        assert cal.find()["silent"] == []


def test_directions_and_a_zero_recovered_on_the_mis_assembled_scara(arm_file):
    """`sim?miscal=7`: the user answers from what the physical arm does (the seed's truth,
    armctl._armctl.testing), jogs one joint to where it truly stands at its zero, and
    confirms; the written file then reads that joint as a well-built arm does, within one
    device unit, and turns it the right way."""
    from armctl._armctl import testing

    seed = 7
    truth = testing.miscalibration("scara", seed)
    by_id = {t["id"]: t for t in truth["joints"]}
    device = f"sim?miscal={seed}"

    def true_position(joint_id, d):
        t = by_id[joint_id]
        return truth["pivot"] + (-1 if t["flipped"] else 1) * (d - truth["pivot"]) + t["zero_shift"]

    with armctl.Arm(str(arm_file), device) as arm:
        joints = arm.joints
        j = arm.joint_names.index(JOINT)
        ident = joints[j].joint_bus_id
        with arm.calibration() as cal:
            # The SCARA's arm joints; its wrist (SKE, SKF) is a differential pair, where one
            # device's motion is not one joint's (the C++ engine tests answer those from the
            # simulator's joint truth).
            for i, joint in enumerate(joints):
                if joint.name not in ("SHOULDER", "UAE", "UAJ"):
                    continue
                # The user sees the joint turn the way a well-built one turns when its true
                # position grows.
                before = arm.read().device[i]
                cal.nudge(i)
                after = arm.read().device[i]
                went_as_shown = true_position(joint.joint_bus_id, after) > true_position(joint.joint_bus_id, before)
                cal.answer_direction(i, went_as_shown)
            flipped = {c["joint"] for c in cal.changes()["joints"] if c["flip"]}
            assert flipped == {joints[t["id"] - 1].name for t in truth["joints"] if t["flipped"]} == {JOINT}  # seed 7

            # Zero: the shipped file's zero is where a well-built joint's device reads what
            # this file's zero reads now (device units per rad from two readings).
            s0 = arm.read()
            arm.move_joints({j: s0.positions[j] + 0.1}, wait=True)
            s1 = arm.read()
            per_rad = (s1.device[j] - s0.device[j]) / (s1.positions[j] - s0.positions[j])
            file_zero = s1.device[j] - s1.positions[j] * per_rad  # device at reading 0, shipped file
            # The device position where the joint truly stands at the file's zero.
            t = by_id[ident]
            sign = -1 if t["flipped"] else 1
            true_zero = truth["pivot"] + sign * (file_zero - t["zero_shift"] - truth["pivot"])
            arm.move_joints({j: s1.positions[j] + (true_zero - s1.device[j]) / per_rad}, wait=True)
            cal.zero_here(j, 0.0)
            cal.confirm()

    with armctl.Arm(str(arm_file), device) as arm:
        # A fresh simulator: the written file reads the joint as the shipped file reads a
        # well-built one, wherever it stands (within a device unit), and the right way round.
        def well_built_reading(d):
            return (true_position(ident, d) - file_zero) / per_rad

        s = arm.read()
        assert s.positions[j] == pytest.approx(well_built_reading(s.device[j]), abs=1.0 / abs(per_rad))
        arm.move_joints({j: s.positions[j] + 0.1}, wait=True)
        s = arm.read()
        assert s.positions[j] == pytest.approx(well_built_reading(s.device[j]), abs=1.0 / abs(per_rad))



@pytest.fixture
def xarm_file(tmp_path):
    return copy_of_shipped_arm(tmp_path, "xarm")


def test_limits_gripper_and_touched_points_on_the_xarm(xarm_file):
    """Steps 5 to 7 from Python on the embedded xArm: limits from two ends pulled in by the
    margin (3 deg), limits that exclude the zero refused; the gripper's open and closed
    readings; points touched where the sheet has them verify within the servos' resolution,
    and one given 20 mm off is the worst by about 20 mm. Confirm writes limits and gripper."""
    import json
    import math

    margin = math.radians(3)
    with armctl.Arm(str(xarm_file)) as arm, arm.calibration() as cal:
        limits = cal.limits("servo3", 1.6, -1.5)  # either order
        assert limits["lower"] == pytest.approx(-1.5 + margin, abs=1e-6)
        assert limits["upper"] == pytest.approx(1.6 - margin, abs=1e-6)
        with pytest.raises(armctl.Error) as e:
            cal.limits("servo4", 0.3, 1.0)  # the joint's zero would be outside
        assert e.value.kind == "invalid_argument"
        assert "zero" in str(e.value)

        grip = cal.gripper(-1.2, 0.8)
        assert grip["open"] == pytest.approx(-1.2, abs=1e-6)
        assert grip["closed"] == pytest.approx(0.8, abs=1e-6)
        with pytest.raises(armctl.Error):
            cal.gripper(0.10, 0.11)  # open and closed cannot be told apart

        # The tool is put 5 mm above the three marks farthest out (C, D, E), each point given
        # as where it stands. (Nearer the base, at A and B, the fingers come within the base
        # plate's collision box, which a planned move refuses; a user touching by hand in the
        # wizard has the torque off.)
        marks = [{"name": m["name"], "position": [m["position"][0], m["position"][1], m["position"][2] + 0.005]}
                 for m in cal.sheet_points()[2:]]
        assert len(marks) == 3
        for mark in marks:
            arm.move_to(mark["position"], wait=True)
            cal.touch(mark["name"], mark["position"])
        report = cal.verify()
        assert [p["name"] for p in report["points"]] == [m["name"] for m in marks]
        assert report["max"] < 0.003  # a well-built arm: within its servos' 0.24 deg steps
        # The user put the tool on the wrong mark: 20 mm from where they said it stands.
        wrong = list(marks[-1]["position"])
        wrong[0] += 0.020
        cal.touch(marks[-1]["name"], wrong)  # touching a name again replaces it
        report = cal.verify()
        assert report["worst"] == marks[-1]["name"]
        assert report["max"] == pytest.approx(0.020, abs=0.003)
        cal.forget()
        cal.limits("servo3", 1.6, -1.5)
        cal.gripper(-1.2, 0.8)
        written = cal.confirm()

    data = json.loads(Path(written["file"]).read_text())
    servo3 = next(j for j in data["joints"] if j["name"] == "servo3")
    low, high = servo3["limits"]["position"]
    # Written in the file's own units (deg), as the steps gave them.
    assert float(low.removesuffix("deg")) == pytest.approx(math.degrees(-1.5 + margin), abs=1e-3)
    assert float(high.removesuffix("deg")) == pytest.approx(math.degrees(1.6 - margin), abs=1e-3)
    assert float(data["gripper"]["open"].removesuffix("deg")) == pytest.approx(math.degrees(-1.2), abs=1e-3)
    assert float(data["gripper"]["closed"].removesuffix("deg")) == pytest.approx(math.degrees(0.8), abs=1e-3)

def test_the_docs_example_runs_as_printed(tmp_path, monkeypatch):
    """docs/calibration.md "Python", in a folder with the copy it asks for."""
    docs = (Path(__file__).resolve().parents[2] / "docs" / "calibration.md").read_text()
    section = re.search(r"^## Python\n(.*?)(?=^## )", docs, re.S | re.M).group(1)
    (example,) = re.findall(r"^```python\n(.*?)^```", section, re.S | re.M)
    (tmp_path / "myarm").mkdir()
    for name in ("scara.arm.json", "scara.urdf"):
        shutil.copy(CONFIG / name, tmp_path / "myarm" / name)
    run = subprocess.run([sys.executable, "-c", example], cwd=tmp_path, env=script_env(), capture_output=True,
                         text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert "direction flipped" in run.stdout
    assert (tmp_path / "myarm" / "scara.arm.json.prev").exists()


def test_the_fit_finds_a_wrong_link_length_and_the_arm_drives_with_it_after_confirm(xarm_file):
    """Step 8 from Python: an arm file whose servo3 link says 100.5 mm where the embedded xArm
    is built with the shipped 96.5 mm. The tool is put at 16 poses and each point given where
    the tool truly stands (the shipped arm's forward kinematics: what a ruler would read). The
    fit finds the 4 mm, its residuals fall below half a millimetre, and after confirm the same
    Arm puts the tool where it truly is, at a pose the fit never saw."""
    import json
    import math

    data = json.loads(xarm_file.read_text())
    data["link_lengths"] = {"servo3": "100.500000mm"}
    xarm_file.write_text(json.dumps(data, indent=2))
    truth = armctl.Arm(str(CONFIG / "xarm.arm.json"))  # forward kinematics only: nothing sent
    poses = [[0.7 * math.sin(1.3 * i), 0.5 * math.sin(0.9 * i + 1), 0.8 * math.cos(0.7 * i),
              0.6 * math.sin(1.7 * i + 2), 0.4 * math.cos(2.3 * i)] for i in range(16)]
    unseen = [0.3, -0.4, 0.5, 0.2, -0.1]
    try:
        with armctl.Arm(str(xarm_file)) as arm:
            with arm.calibration() as cal:
                for i, q in enumerate(poses):
                    arm.move_joints(q + [None], speed=1.0, wait=True)
                    stands = arm.read().positions[:5]
                    cal.touch(f"P{i + 1}", list(truth.forward(stands).position))
                before = cal.verify()
                fit = cal.fit()
                after = cal.verify()
                lengths = {e["joint"]: e for e in fit["estimates"] if e["kind"] == "length"}
                assert "servo3" in lengths, fit["estimates"]
                assert lengths["servo3"]["correction"] == pytest.approx(-0.004, abs=0.0005)
                assert before["rms"] > 0.002  # 4 mm of link shows at the tool
                assert after["rms"] < 0.0005
                cal.confirm()
            # The same Arm, no reopening: its forward kinematics are the true arm's.
            got = arm.forward(unseen).position
            want = truth.forward(unseen).position
            assert math.dist(got, want) < 0.0005
    finally:
        truth.close()
    written = json.loads(xarm_file.read_text())
    assert float(written["link_lengths"]["servo3"].removesuffix("mm")) == pytest.approx(96.5, abs=0.5)
