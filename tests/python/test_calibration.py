"""armctl.Calibration (docs/calibration.md "Python"): the wizard's steps on the embedded SCARA
simulator with an arm file of the test's own, answered as a user would: the joint went the
other way than the picture shows, and it stands at its mark. Confirm writes the file (the old
one kept beside it); a block left without confirm writes nothing."""

import os
import shutil
from pathlib import Path

import pytest

import armctl

CONFIG = Path(os.environ.get("ARMCTL_CONFIG_DIR", Path(__file__).resolve().parents[2] / "config"))
JOINT = "UAE"  # a revolute chain joint of the SCARA


@pytest.fixture
def arm_file(tmp_path):
    folder = tmp_path / "arm"
    folder.mkdir()
    for name in ("scara.arm.json", "scara.urdf"):
        shutil.copy(CONFIG / name, folder / name)
    return folder / "scara.arm.json"


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
