"""Robot programs from Python (docs/programs.md): check before anything moves, run, and the
errors armctl.Error carries."""

import os
import pathlib

import pytest

import armctl

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples" / "programs"


def test_check_plans_the_shipped_example_without_moving(xarm):
    before = xarm.read().positions.copy()
    c = xarm.check_program(str(EXAMPLES / "xarm-pick-place.prog"))  # points found beside it
    assert c["moves"] > 10 and c["pieces"] > 5
    assert 10 < c["duration"] < 120
    assert (xarm.read().positions == before).all()


def test_an_unreachable_point_is_refused_naming_the_line(xarm, tmp_path):
    prog = tmp_path / "far.prog"
    prog.write_text("lin far speed=40mm/s\n")
    points = tmp_path / "far.points"
    points.write_text("far x=900mm y=0mm z=100mm\n")
    with pytest.raises(armctl.Error) as e:
        xarm.check_program(str(prog), str(points))
    assert e.value.kind == "invalid_argument"
    assert "far.prog:1" in str(e.value)
    assert e.value.detail == "source_place"
    assert (e.value.file, e.value.line) == (str(prog), 1)


def test_a_syntax_error_names_line_and_column(xarm, tmp_path):
    prog = tmp_path / "bad.prog"
    prog.write_text("wait 1s\nlin\n")
    with pytest.raises(armctl.Error) as e:
        xarm.check_program(str(prog))
    assert "bad.prog:2:" in str(e.value)
    assert e.value.detail == "source_place"
    assert (e.value.file, e.value.line, e.value.column) == (str(prog), 2, 4)


def test_run_moves_the_arm_and_reports_what_it_printed(xarm, tmp_path):
    prog = tmp_path / "short.prog"
    prog.write_text("print \"start\"\nptp a speed=50%\nlin b speed=50mm/s\nprint \"done\"\n")
    points = tmp_path / "short.points"
    points.write_text("a x=180mm y=-20mm z=100mm pitch=50deg\nb x=180mm y=20mm z=100mm pitch=50deg\n")
    r = xarm.run_program(str(prog), str(points))
    assert r["completed"] and r["pieces"] >= 2
    assert r["printed"] == ["start", "done"]
    xarm.wait()
    assert xarm.pose().position[1] == pytest.approx(0.02, abs=0.003)
