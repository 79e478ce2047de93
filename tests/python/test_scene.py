"""A scene file from Python (docs/scene.md): armctl.Arm(scene=...) and arm.scene check every
motion before it starts, a refusal carries the two bodies as e.detail 'collision', and a bad
file is refused with its key while the scene before it stays."""

from pathlib import Path

import pytest

import armctl

ROOT = Path(__file__).resolve().parents[2]
DESK = str(ROOT / "examples" / "scenes" / "xarm-desk.json")


def test_a_move_into_the_box_is_refused_with_both_bodies():
    with armctl.Arm("xarm", scene=DESK) as arm:
        assert arm.scene == DESK
        before = arm.read().positions.copy()
        with pytest.raises(armctl.Error) as e:
            arm.move_to([0.150, -0.100, 0.060])
        assert e.value.kind == "invalid_argument"
        assert e.value.detail == "collision"
        assert e.value.bodies[1] == "box 'box'"
        assert 0 < e.value.depth < 0.002
        assert 0 < e.value.fraction <= 1
        assert len(e.value.point) == 3
        assert list(arm.read().positions) == list(before)  # nothing moved


def test_the_scene_is_set_cleared_and_a_bad_file_keeps_the_old_one(tmp_path):
    with armctl.Arm("xarm") as arm:
        assert arm.scene is None
        arm.scene = DESK
        assert arm.scene == DESK
        bad = tmp_path / "bad.json"
        bad.write_text('{"objects": [{"name": "box", "sphere": {"radius": -1}, "at": [0, 0, 0]}]}')
        with pytest.raises(armctl.Error) as e:
            arm.scene = str(bad)
        assert e.value.kind == "invalid_config"
        assert "objects[0].sphere.radius" in str(e.value)
        assert arm.scene == DESK
        arm.scene = None
        assert arm.scene is None
        arm.move_to([0.150, -0.100, 0.060], wait=True)  # without the box it moves
