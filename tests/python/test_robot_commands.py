"""armctl.RobotCommands, the Robot Commands client in device units, on the emulated xArm."""

import time

import pytest

import armctl


@pytest.fixture
def board():
    with armctl.RobotCommands("sim") as b:
        yield b


def test_move_and_read_back(board):
    assert board.servo_count == 6
    assert [sid for sid, _ in board.read_positions()] == [1, 2, 3, 4, 5, 6]
    board.move([(1, 600), (2, None)], 200)
    time.sleep(0.35)
    read = dict(board.read_positions([1, 2]))
    assert abs(read[1] - 600) <= 1
    assert 5000 < board.battery_millivolts() < 13000


def test_offsets_and_torque(board):
    board.adjust_offset(3, 20)
    assert dict(board.read_offsets([3]))[3] == 20
    board.save_offsets([3])
    board.servos_off([1, 2])
    board.servos_off()


def test_groups(board):
    board.download_group(1, "servos 1\n100 1=510\n100 1=500\n")
    board.set_group_speed(1, 200)
    board.run_group(1, 2)
    kinds = []
    deadline = time.monotonic() + 5
    while "finished" not in kinds and time.monotonic() < deadline:
        kinds += [e["kind"] for e in board.group_events(timeout=0.5)]
    assert kinds[0] == "started" and "finished" in kinds


@pytest.mark.parametrize("call, kind", [
    (lambda b: b.move([(1, 1001)], 100), "invalid_argument"),
    (lambda b: b.move([(0, 500)], 100), "invalid_argument"),
    (lambda b: b.move([(1, 500)], 40000), "invalid_argument"),
    (lambda b: b.read_positions([300]), "invalid_argument"),
    (lambda b: b.adjust_offset(1, 200), "invalid_argument"),
    (lambda b: b.run_group(1, -1), "invalid_argument"),
    (lambda b: b.download_group(1, "nonsense"), "invalid_config"),
    (lambda b: b.group_events(timeout=-1), "invalid_argument"),
])
def test_refusals(board, call, kind):
    before = board.read_positions()
    with pytest.raises(armctl.Error) as e:
        call(board)
    assert e.value.kind == kind, e.value.message
    assert board.read_positions() == before


def test_bad_uris_and_timeouts():
    with pytest.raises(armctl.Error) as e:
        armctl.RobotCommands("bogus:thing")
    assert e.value.kind == "invalid_argument"
    with pytest.raises(armctl.Error) as e:
        armctl.RobotCommands("sim", timeout=-1)
    assert e.value.kind == "invalid_argument"
    with pytest.raises(armctl.Error) as e:
        armctl.RobotCommands("sim", servo_count=40)
    assert e.value.kind == "invalid_argument"
