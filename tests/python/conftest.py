"""Shared fixtures: every test runs against the embedded simulators, with the emulated xArm's
persistent state (groups, offsets) in a fresh folder of its own."""

import os
import sys

import pytest

import armctl


@pytest.fixture(autouse=True)
def state_dir(tmp_path, monkeypatch):
    monkeypatch.setenv("ARMCTL_STATE_DIR", str(tmp_path / "state"))
    return tmp_path / "state"


@pytest.fixture
def xarm():
    with armctl.Arm() as arm:
        yield arm


@pytest.fixture
def scara():
    with armctl.Arm("scara") as arm:
        yield arm


def script_env():
    """The environment for a script run as a child: this package importable."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p)
    return env
