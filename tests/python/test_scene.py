"""A scene file from Python (docs/scene.md): armctl.Arm(scene=...) and arm.scene check every
motion before it starts, a refusal carries the two bodies as e.detail 'collision', and a bad
file is refused with its key while the scene before it stays. Its fence and reduced mode,
on both arms: a move out of the fence refused (e.detail 'limit') until arm.fence is switched
off, a joint move beyond a reduced range refused while arm.reduced_mode is on."""

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


FENCED = '{"fence": {"min": [-800, -800, -100], "max": [800, 100, 800]}, "reduced": {"tool_speed": 20, "joints": {"servo5": [-20, 20]}, "on": false}}'


@pytest.mark.parametrize("name,target", [("xarm", [0.150, 0.150, 0.200]), ("scara", [0.400, 0.400, 0.250])])
def test_the_fence_refuses_a_move_out_of_it_until_switched_off(tmp_path, name, target):
    scene = tmp_path / "fenced.json"
    joint = "SHOULDER" if name == "scara" else "servo5"
    scene.write_text(FENCED.replace("servo5", joint))
    with armctl.Arm(name, scene=str(scene)) as arm:
        assert arm.fence is True
        assert arm.reduced_mode is False
        before = arm.read().positions.copy()
        with pytest.raises(armctl.Error) as e:
            arm.move_to(target)
        assert e.value.detail == "limit"
        assert e.value.broken_limit == "fence"
        assert e.value.bodies == ("the tool point", "the fence")
        assert e.value.point[1] > 0.099
        assert list(arm.read().positions) == list(before)  # nothing moved
        arm.fence = False
        assert arm.fence is False
        arm.reduced_mode = True
        with pytest.raises(armctl.Error) as e:
            arm.move_joints({joint: 0.6})
        assert e.value.broken_limit == "joint range"
        arm.reduced_mode = False
        arm.move_to(target, wait=True)


def test_switching_a_limit_the_scene_does_not_set_raises():
    with armctl.Arm("xarm") as arm:
        assert arm.fence is None
        assert arm.reduced_mode is None
        with pytest.raises(armctl.Error) as e:
            arm.fence = True
        assert "the scene sets no fence, nor does the arm file" in str(e.value)
