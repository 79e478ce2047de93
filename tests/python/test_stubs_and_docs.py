"""The .pyi stub names every call the native module has (and nothing it lacks), and every
call has a docstring, so that help() and editors explain them."""

import ast
import inspect
from pathlib import Path

import armctl
from armctl import _armctl

STUB = Path(_armctl.__file__).parent / "_armctl.pyi"


def public(names):
    return {n for n in names if not n.startswith("_")}


def stub_tree():
    tree = ast.parse(STUB.read_text())
    top, classes = set(), {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            top.add(node.name)
            classes[node.name] = public(n.name for n in node.body if isinstance(n, ast.FunctionDef))
        elif isinstance(node, ast.FunctionDef):
            top.add(node.name)
    return top, classes


def test_the_stub_matches_the_module():
    top, classes = stub_tree()
    native = public(n for n in dir(_armctl) if not inspect.ismodule(getattr(_armctl, n)))
    assert native == top
    for name, methods in classes.items():
        cls = getattr(_armctl, name)
        if name == "Error":
            continue
        assert public(dir(cls)) == methods, name


def test_every_call_has_a_docstring():
    assert _armctl.__doc__ and armctl.__doc__
    missing = []
    for name in public(dir(_armctl)):
        obj = getattr(_armctl, name)
        if not obj.__doc__:
            missing.append(name)
        if inspect.isclass(obj) and name != "Error":
            missing += [f"{name}.{m}" for m in public(dir(obj)) if not getattr(obj, m).__doc__]
    assert missing == []


def test_the_drop_in_is_documented():
    import armctl.xarm as xarm

    for obj in (xarm, xarm.Controller, xarm.Servo):
        assert obj.__doc__
    for name in public(dir(xarm.Controller)):
        assert getattr(xarm.Controller, name).__doc__, name


def test_the_version_is_the_clis():
    """armctl.__version__ is the version `armctl --version` prints (one project version)."""
    import os
    import subprocess

    cli = os.environ["ARMCTL_CLI"]
    printed = subprocess.run([cli, "--version"], capture_output=True, text=True, check=True).stdout.split()
    assert printed == ["armctl", armctl.__version__]
    assert armctl.__version__.count(".") == 2
