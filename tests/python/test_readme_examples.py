"""The examples of README.md and docs/ run exactly as printed, against the embedded
simulators, so that the documentation cannot rot: each `armctl` line of the sections below
(the CLI of this build in place of `build/armctl` or `armctl`) must exit 0, and the README's
Python lines must run in order in one interpreter without raising. A server (`armctl serve`)
must come up and say where to open it, then stop on Ctrl-C with status 0.

Each `armctl` command starts its own embedded simulator: the xArm in its start pose, every
servo centred (the arm straight up, a singular pose), as a user's first command finds it."""

import atexit
import os
import re
import shlex
import shutil
import signal
import socket
import subprocess
import time
import tempfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CLI = os.environ.get("ARMCTL_CLI", str(ROOT / "build" / "armctl"))

# Where the commands run, in order: a folder of their own that sees the source tree's
# examples/ and config/ as a user's checkout does, so that what they write (teach's wave.rec,
# read by the replay after it) stays out of the tree.
WORK = Path(tempfile.mkdtemp(prefix="armctl-readme-"))
atexit.register(shutil.rmtree, WORK, ignore_errors=True)
for folder in ("examples", "config"):
    (WORK / folder).symlink_to(ROOT / folder)

# (file, section heading): the sections whose examples are run; None: the whole file.
SECTIONS = [
    ("README.md", "Move the tool to a point in millimetres"),
    ("README.md", "Follow a line, blend corners, stop on the path"),
    ("README.md", "Python"),
    ("README.md", "Write robot programs"),
    ("README.md", "Teach by hand, record and replay"),
    ("README.md", "Keep clear of the table and what stands on it"),
    ("README.md", "Jog: drive the arm from the keyboard"),
    ("docs/scene.md", None),
    ("docs/motion.md", "From the command line"),
    ("docs/programs.md", None),
    ("docs/teach.md", None),
    ("docs/dashboard.md", None),
]

HARDWARE = "needs a real arm (a USB HID board)"
# Commands not run, each with why, word for word: those that need hardware or another process.
SKIPPED = {
    "armctl program compile examples/programs/xarm-pick-place.prog --group 3 --device hid": HARDWARE,
    "armctl teach --arm xarm --device hid --points pick.points": HARDWARE,
    "armctl xarm group import examples/groups/wave.rob --group 3 --device hid   # and download it as group 3": HARDWARE,
    "build/armctl serve --device /dev/hidraw0 --points cell.points   # a real xArm; points saved to a file": HARDWARE,
    "build/armctl serve --listen 0.0.0.0:8080   # the LAN: prints http://HOST:8080/?token=T, open that URL":
        "listens on every interface; tests stay on the loopback (tests/web covers the token off it)",
    "ARMCTL_CLI=build/armctl node --test tests/browser/dashboard_xarm.test.mjs":
        "the browser test itself, which CTest runs (browser.dashboard_xarm)",
}


# Commands printed to show a refusal: each must exit 1 with these words on stderr (the
# refusal comes before anything moves).
REFUSED = {
    "build/armctl arm --scene examples/scenes/xarm-desk.json move-to x=150 y=-100 z=60": "with box 'box'",
    # A simulator with a box the host does not know: the servo stalls at it (stall protection).
    "build/armctl arm --arm xarm --device /tmp/xarm-desk move-to x=150 y=-100 z=60 --wait": "stalled",
    "build/armctl arm --arm scara --device unix:/tmp/scara.sock move-joints Z=50mm --wait": "joint Z stalled",
    "build/armctl arm --scene examples/scenes/xarm-desk.json move-to x=120 y=120 z=-5": "with the table 'desk'",
    "build/armctl arm --scene examples/scenes/xarm-desk.json move-to x=150 y=-190 z=40": "with box 'box'",
}


def fenced_blocks(file, heading):
    """The (language, text) of each fenced block in the section `## heading` of `file` (all
    of the file for None)."""
    text = (ROOT / file).read_text()
    if heading is not None:
        match = re.search(rf"^## {re.escape(heading)}\n(.*?)(?=^## |\Z)", text, re.S | re.M)
        assert match, f"{file}: no section '## {heading}'"
        text = match.group(1)
    return re.findall(r"^```(\w*)\n(.*?)^```", text, re.S | re.M)


def command_lines(file, heading):
    """The `armctl` command lines of the section's sh blocks, as printed."""
    lines = []
    for language, block in fenced_blocks(file, heading):
        if language != "sh":
            continue  # `planned 5 moves ...`: output, not a command
        for line in block.splitlines():
            if line.strip() and not line.lstrip().startswith("#"):
                lines.append(line)
    return lines


# Simulators printed to run in the background (`... &`): started, left running for the lines
# after them, ended when this module's tests are done.
BACKGROUND = []


@pytest.fixture(scope="module", autouse=True)
def end_background():
    yield
    for process in BACKGROUND:
        process.send_signal(signal.SIGINT)
        try:
            process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()


def run_in_background(file, line):
    """Starts `line` (without its `&`) and waits for the pty link (--link PATH) or the socket
    (--listen PATH) it names to appear."""
    words = shlex.split(line.rsplit("&", 1)[0], comments=True)
    option = next((o for o in ("--link", "--listen") if o in words), None)
    assert option, f"{file}: {line}\na background simulator needs --link or --listen PATH for the lines after it"
    link = Path(words[words.index(option) + 1])
    # One left by an earlier run would look ready before this simulator is.
    if link.is_symlink() or link.is_socket():
        link.unlink()
    process = subprocess.Popen([CLI] + words[1:], cwd=WORK, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                               stderr=subprocess.PIPE, text=True)
    BACKGROUND.append(process)
    deadline = time.monotonic() + 60
    while not link.exists():
        assert process.poll() is None, f"{file}: {line}\nexit {process.returncode}\n{process.stderr.read()}"
        assert time.monotonic() < deadline, f"{file}: {line}\n{link} never appeared"
        time.sleep(0.05)  # polling for the link, not settling


def is_server(line):
    return re.match(r"(build/)?armctl serve\b", line) is not None


def port_taken(port):
    with socket.socket() as s:
        return s.connect_ex(("127.0.0.1", port)) == 0


def run_server(file, line):
    """Starts the server as printed, waits for the URL it prints, stops it with Ctrl-C."""
    if port_taken(8080):
        pytest.skip("something on this machine already listens on 127.0.0.1:8080, where the example serves")
    server = subprocess.Popen(argv_of(line), cwd=WORK, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True)
    said = []
    try:
        for out in server.stdout:  # blocks per line; the server ends the loop if it exits
            said.append(out)
            if out.startswith("open http://127.0.0.1:8080/"):
                break
        assert said and said[-1].startswith("open http"), f"{file}: {line}\nno URL printed:\n{''.join(said)}"
        server.send_signal(signal.SIGINT)
        rest, _ = server.communicate(timeout=60)
    finally:
        if server.poll() is None:
            server.kill()
            server.wait()
    assert server.returncode == 0, f"{file}: {line}\nexit {server.returncode}\n{''.join(said)}{rest}"


def argv_of(line):
    """The line's words (its comment dropped), with this build's CLI for the program; a
    pipeline into armctl (`printf 'home\\n' | build/armctl teach ...`) runs in bash as printed."""
    words = shlex.split(line, comments=True)
    if words[0] not in ("build/armctl", "armctl") and "|" in words:
        assert words[words.index("|") + 1] in ("build/armctl", "armctl"), f"not a pipe into armctl: {line}"
        return ["bash", "-o", "pipefail", "-c", re.sub(r"(^|\| )(build/)?armctl ", rf"\1{shlex.quote(CLI)} ", line)]
    assert words[0] in ("build/armctl", "armctl"), f"not an armctl command: {line}"
    return [CLI] + words[1:]


COMMANDS = [(file, line) for file, heading in SECTIONS if heading != "Python" for line in command_lines(file, heading)]


def test_every_section_has_examples():
    for file, heading in SECTIONS:
        blocks = fenced_blocks(file, heading)
        assert blocks, f"{file}: '## {heading}' has no fenced block"
    assert len(COMMANDS) >= 39  # README: 8 + 3 + 3 + 4 + 3 commands; motion.md's 4; programs, teach, dashboard: 18
    for line in SKIPPED:
        assert any(line == command for _, command in COMMANDS), f"skipped but no longer in the docs: {line}"


@pytest.mark.parametrize("file,line", COMMANDS, ids=[line.split("#")[0].strip() for _, line in COMMANDS])
def test_command_runs_as_printed(file, line):
    if line in SKIPPED:
        pytest.skip(SKIPPED[line])
    if is_server(line):
        run_server(file, line)
        return
    if line.split("#")[0].rstrip().endswith("&"):
        run_in_background(file, line)
        return
    run = subprocess.run(argv_of(line), cwd=WORK, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                         timeout=180)
    command = line.split("#")[0].strip()
    if command in REFUSED:
        assert run.returncode == 1 and REFUSED[command] in run.stderr, \
            f"{file}: {line}\nexit {run.returncode} (a refusal naming \"{REFUSED[command]}\" expected)\n{run.stdout}\n{run.stderr}"
        return
    assert run.returncode == 0, f"{file}: {line}\nexit {run.returncode}\n{run.stdout}\n{run.stderr}"


def test_the_python_lines_run_as_printed():
    """The README's Python block, line by line in one namespace, as a user types them."""
    blocks = [text for language, text in fenced_blocks("README.md", "Python") if language == "python"]
    assert len(blocks) == 1
    lines = [line for line in blocks[0].splitlines() if line.strip()]
    assert any("move_linear" in line for line in lines)
    namespace = {}
    try:
        for number, line in enumerate(lines, 1):
            try:
                exec(compile(line, f"README.md Python line {number}", "single"), namespace)
            except Exception as e:  # noqa: BLE001 (which line failed, and why)
                pytest.fail(f"README.md's Python line {number} failed: {line}\n{type(e).__name__}: {e}")
    finally:
        if "arm" in namespace:
            namespace["arm"].close()
