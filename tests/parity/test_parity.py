"""Parity: the same scenario through every app on each simulated arm (issue 20).

The CLI (`armctl arm --json`, `armctl program`), the Python module (`armctl.Arm`), the HTTP
API (`armctl serve`) and the ROS node (`armctl_ros`, its `~move_to` service) all plan and run
through the one planner and runner (docs/architecture.md "One motion service under every
app"). Here each app, on its own fresh embedded simulator of the same arm, is asked:

1. a PTP to a tool pose (position and orientation given): the planned duration (within
   1 ms), the planned joint targets (within 1e-6 of SI) and the pose the arm ends at (within
   the arrival tolerance) must be the same in every app;
2. a LIN run with a zone (a program: CLI, Python, HTTP; ROS takes no programs): the same
   planned duration, and the same end;
3. an unreachable pose: the same refusal, kind and message, and nothing moves;
4. a stop during a long move: every app says it stopped, and the arm is at rest short of the
   target.

What differs by design, and is not compared here: a second move while one runs is refused
as busy by the HTTP API, replaces the running one in ROS (a ROS motion lane), and is a new
board move in the CLI and Python (docs/architecture.md says why).

Error kinds: the CLI, HTTP and ROS name them as armctl does ("invalid argument"); Python's
`armctl.Error.kind` is the identifier spelling ("invalid_argument"), compared with "_" read as " ".
"""

import json
import math
import os
import signal
import socket
import subprocess
import tempfile
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

import armctl

ROOT = Path(__file__).resolve().parents[2]
CLI = os.environ["ARMCTL_CLI"]
ROS_NODE = os.environ["ARMCTL_ROS_NODE"]
# Children (armctl, rosmaster, the node) run without the ASan runtime this Python preloads.
CHILD_ENV = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}
APPS = ["cli", "python", "http", "ros"]
ARMS = ["xarm", "scara"]
DEG = math.pi / 180
DURATION_TOLERANCE = 1e-3  # s
TARGET_TOLERANCE = 1e-6    # rad or m
ARRIVAL = {"angle": 0.02, "length": 0.002}  # rad, m: two apps' end poses, each within arrival of the target


# ------------------------------------------------------------------------ the scenario


def scenario(arm_name):
    """The pose every app is asked to reach: the forward kinematics of joints inside every
    limit (so it is reachable), with its orientation as armctl reads it (Arm.pose's
    roll/pitch/yaw) and as a quaternion for ROS; and a point beyond reach."""
    with armctl.Arm(arm_name) as arm:
        q = [j.lower + 0.62 * (j.upper - j.lower) for j in arm.joints[: arm.chain_joints]]
        pose = arm.forward(q)
    position = [round(v * 1e3, 6) / 1e3 for v in pose.position]  # what the CLI's mm text carries
    rpy = [round(v / DEG, 6) * DEG for v in (pose.roll, pose.pitch, pose.yaw)]
    return {
        "position": position,
        "rpy": rpy,
        "quaternion": list(pose.orientation),
        "unreachable": [1.5, 0.0, 0.1],
    }


def program_files(arm_name, folder):
    """A program of a PTP and two LINs blended by a zone, on the shipped points of that arm."""
    points = ROOT / "examples" / "programs" / f"{arm_name}-pick-place.points"
    source = ("ptp home\n"
              "lin pick + base(z=40mm) speed=60mm/s zone=10mm\n"
              "lin place + base(z=40mm) speed=60mm/s\n")
    program = Path(folder) / f"parity-{arm_name}.prog"
    program.write_text(source)
    return program, points


# ------------------------------------------------------------------------ the CLI


class Cli:
    def __init__(self, arm_name):
        self.arm = arm_name

    def run(self, *args):
        r = subprocess.run([CLI, *args], capture_output=True, text=True, env=CHILD_ENV, timeout=300)
        return r.returncode, [json.loads(line) for line in r.stdout.splitlines() if line.strip()], r.stderr

    def move_args(self, position, rpy):
        mm = [f"{v * 1e3:.6f}mm" for v in position]
        deg = [f"{v / DEG:.6f}deg" for v in rpy]
        return [f"x={mm[0]}", f"y={mm[1]}", f"z={mm[2]}", f"roll={deg[0]}", f"pitch={deg[1]}", f"yaw={deg[2]}"]

    def ptp(self, s):
        status, docs, err = self.run("arm", "--arm", self.arm, "--json", "move-to",
                                     *self.move_args(s["position"], s["rpy"]), "--wait")
        assert status == 0, err
        planned, arrived = docs[0], docs[-1]
        assert planned["event"] == "planned", docs
        return {"duration": planned["duration_s"], "targets": [t["si"] for t in planned["targets"]],
                "end": [j["si"] for j in arrived["joints"]]}

    def refusal(self, s):
        status, docs, _ = self.run("arm", "--arm", self.arm, "--json", "move-to",
                                   *self.move_args(s["unreachable"], s["rpy"]), "--wait")
        assert status == 1, docs
        assert [d["event"] for d in docs] == ["error"], docs  # nothing planned, nothing moved
        return {"kind": docs[0]["kind"], "message": docs[0]["message"]}

    def program(self, program, points):
        status, docs, err = self.run("program", "run", str(program), "--arm", self.arm, "--points", str(points),
                                     "--json")
        assert status == 0, err
        planned = next(d for d in docs if d["event"] == "planned")
        assert docs[-1]["event"] == "finished", docs
        return {"duration": planned["duration_s"]}

    def stop(self, s):
        """Ctrl-C during a slow move: exit 130, the arm halted (the embedded arm ends with it)."""
        p = subprocess.Popen([CLI, "arm", "--arm", self.arm, "--json", "move-to",
                              *self.move_args(s["position"], s["rpy"]), "--speed", "5%", "--wait"],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=CHILD_ENV)
        first = json.loads(p.stdout.readline())
        assert first["event"] == "planned", first
        p.send_signal(signal.SIGINT)
        out, err = p.communicate(timeout=60)
        assert p.returncode == 130, (out, err)
        return {"stopped": True, "message": err.strip()}


# ------------------------------------------------------------------------ Python


class Python:
    def __init__(self, arm_name):
        self.arm_name = arm_name

    def ptp(self, s):
        with armctl.Arm(self.arm_name) as arm:
            roll, pitch, yaw = s["rpy"]
            planned = arm.move_to(s["position"], roll=roll, pitch=pitch, yaw=yaw, wait=True)
            return {"duration": planned.duration, "targets": list(planned.targets), "end": list(arm.read().positions)}

    def refusal(self, s):
        with armctl.Arm(self.arm_name) as arm:
            before = list(arm.read().positions)
            roll, pitch, yaw = s["rpy"]
            with pytest.raises(armctl.Error) as e:
                arm.move_to(s["unreachable"], roll=roll, pitch=pitch, yaw=yaw, wait=True)
            assert list(arm.read().positions) == before  # nothing moved
            return {"kind": e.value.kind.replace("_", " "), "message": str(e.value)}

    def program(self, program, points):
        with armctl.Arm(self.arm_name) as arm:
            checked = arm.check_program(str(program), str(points))
            ran = arm.run_program(str(program), str(points))
            assert ran["completed"], ran
            return {"duration": checked["duration"]}

    def stop(self, s):
        """A slow board move, stop() once it is under way: at rest short of its target."""
        with armctl.Arm(self.arm_name) as arm:
            roll, pitch, yaw = s["rpy"]
            start = list(arm.read().positions)
            planned = arm.move_to(s["position"], roll=roll, pitch=pitch, yaw=yaw, speed=0.05)
            deadline = time.monotonic() + 30
            while max(abs(a - b) for a, b in zip(arm.read().positions, start)) < 0.01:
                assert time.monotonic() < deadline, "the move did not start"
            arm.stop()
            at = list(arm.read().positions)
            short = max(abs(a - b) for a, b in zip(at, planned.targets)) > 0.05
            return {"stopped": short, "message": f"at rest {at}, target {list(planned.targets)}"}


# ------------------------------------------------------------------------ the HTTP API


def free_port():
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


class Http:
    """`armctl serve --json` on its embedded arm (in step with the wall clock)."""

    def __init__(self, arm_name):
        self.arm_name = arm_name
        self.server = None

    def start(self):
        self.server = subprocess.Popen([CLI, "serve", "--arm", self.arm_name, "--listen", "127.0.0.1:0", "--json"],
                                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=CHILD_ENV)
        started = json.loads(self.server.stdout.readline())
        assert started["event"] == "started", started
        self.api = started["url"].rstrip("/") + "/api/v1"
        self.call("POST", "/control", {"take": True})
        deadline = time.monotonic() + 60
        while any(j["position"] is None for j in self.state()["joints"]):  # the first read
            assert time.monotonic() < deadline, "no positions read within 60 s"
            time.sleep(0.05)

    def close(self):
        if self.server:
            self.server.send_signal(signal.SIGINT)
            self.server.communicate(timeout=60)
            self.server = None

    def call(self, method, path, body=None):
        data = None if body is None else json.dumps(body).encode()
        req = urllib.request.Request(self.api + path, data=data, method=method,
                                     headers={"Content-Type": "application/json", "X-Armctl-Client": "parity"})
        try:
            with urllib.request.urlopen(req, timeout=60) as r:
                return r.status, json.loads(r.read() or b"null")
        except urllib.error.HTTPError as e:
            return e.code, json.loads(e.read() or b"null")

    def model_units(self):
        _, model = self.call("GET", "/model")
        return [("deg" if j.get("unit", "deg") == "deg" else "mm") for j in model["joints"]]

    def si(self, values):
        """Joint values as the API shows them (deg, mm) -> SI, by each joint's unit."""
        return [v * DEG if unit == "deg" else v / 1e3 for v, unit in zip(values, self.units)]

    def state(self):
        return self.call("GET", "/state")[1]

    def wait_idle(self, timeout=120):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            s = self.state()
            if not s["job"] and (s["program"] is None or s["program"]["state"] != "running"):
                return s
            time.sleep(0.05)
        raise AssertionError("the arm did not finish within the time")

    def tool_body(self, position, rpy):
        return {"x": position[0] * 1e3, "y": position[1] * 1e3, "z": position[2] * 1e3,
                "roll": rpy[0] / DEG, "pitch": rpy[1] / DEG, "yaw": rpy[2] / DEG}

    def ptp(self, s):
        self.start()
        try:
            self.units = self.model_units()
            status, answer = self.call("POST", "/tool", self.tool_body(s["position"], s["rpy"]))
            assert status in (200, 202), answer
            names = [j["name"] for j in self.state()["joints"]]
            targets = self.si([answer["targets"][n] for n in names])
            final = self.wait_idle()
            # Arrival: read until the joints rest (the job ends when the runner has waited).
            return {"duration": answer["duration_s"], "targets": targets,
                    "end": self.si([j["position"] for j in final["joints"]])}
        finally:
            self.close()

    def refusal(self, s):
        self.start()
        try:
            self.units = self.model_units()
            before = [j["position"] for j in self.state()["joints"]]
            status, answer = self.call("POST", "/tool", self.tool_body(s["unreachable"], s["rpy"]))
            assert status == 400, answer
            assert [j["position"] for j in self.wait_idle()["joints"]] == before  # nothing moved
            return {"kind": answer.get("kind"), "message": answer["error"]}
        finally:
            self.close()

    def program(self, program, points):
        self.start()
        try:
            body = {"source": program.read_text(), "points": points.read_text()}
            status, checked = self.call("POST", "/program/check", body)
            assert status == 200 and checked["ok"], checked
            status, started = self.call("POST", "/program/run", body)
            assert status == 202, started
            self.wait_idle()
            return {"duration": checked["duration_s"]}
        finally:
            self.close()

    def stop(self, s):
        self.start()
        try:
            self.units = self.model_units()
            body = dict(self.tool_body(s["position"], s["rpy"]), speed=0.05)
            status, answer = self.call("POST", "/tool", body)
            assert status in (200, 202), answer
            start = self.state()["joints"]
            deadline = time.monotonic() + 30
            while all(abs(a["position"] - b["position"]) < 0.5 for a, b in zip(self.state()["joints"], start)):
                assert time.monotonic() < deadline, "the move did not start"
                time.sleep(0.02)  # a poll interval: the server runs in step with the wall clock
            status, stopped = self.call("POST", "/stop")
            assert status == 200, stopped
            names = [j["name"] for j in self.state()["joints"]]
            target = self.si([answer["targets"][n] for n in names])
            at = self.si([j["position"] for j in self.wait_idle()["joints"]])
            short = max(abs(a - b) for a, b in zip(at, target)) > 0.05
            return {"stopped": short, "message": f"at rest {at}, target {target}"}
        finally:
            self.close()


# ------------------------------------------------------------------------ ROS


class RosMaster:
    """One master on a free port for the whole run: rospy connects to one master per process."""

    master = None

    @classmethod
    def env(cls):
        if cls.master is None:
            home = tempfile.mkdtemp(prefix="armctl-parity-ros-")
            port = free_port()
            os.environ.update(ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOSTNAME="127.0.0.1", ROS_HOME=home,
                              ROS_LOG_DIR=home + "/log")
            cls.child_env = dict(CHILD_ENV, **{k: os.environ[k] for k in
                                               ("ROS_MASTER_URI", "ROS_HOSTNAME", "ROS_HOME", "ROS_LOG_DIR")})
            cls.master = subprocess.Popen(["rosmaster", "--core", "-p", str(port)], stdout=subprocess.DEVNULL,
                                          stderr=subprocess.DEVNULL, env=cls.child_env, start_new_session=True)
            import rospy
            rospy.init_node("armctl_parity", anonymous=True, disable_signals=True)
        return cls.child_env

    @classmethod
    def stop(cls):
        if cls.master is not None:
            os.killpg(cls.master.pid, signal.SIGTERM)
            cls.master.wait(timeout=60)
            cls.master = None


class Ros:
    """The node on its embedded arm, under a name of its own; rospy as a client."""

    def __init__(self, arm_name):
        self.arm_name = arm_name

    def __enter__(self):
        env = RosMaster.env()
        self.name = f"armctl_ros_{self.arm_name}"
        self.node = subprocess.Popen([ROS_NODE, f"_arm:={self.arm_name}", f"__name:={self.name}"],
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env,
                                     start_new_session=True)
        import rospy
        from armctl_msgs.srv import MoveTo
        self.rospy = rospy
        rospy.wait_for_service(f"/{self.name}/move_to", timeout=60)
        self.move_to = rospy.ServiceProxy(f"/{self.name}/move_to", MoveTo)
        return self

    def __exit__(self, *exc):
        os.killpg(self.node.pid, signal.SIGTERM)
        self.node.wait(timeout=60)

    def pose(self, position, quaternion):
        from geometry_msgs.msg import Pose
        p = Pose()
        p.position.x, p.position.y, p.position.z = position
        p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z = quaternion
        return p

    def joints(self):
        from sensor_msgs.msg import JointState
        return list(self.rospy.wait_for_message("/joint_states", JointState, timeout=30).position)

    def ptp(self, s):
        r = self.move_to(self.pose(s["position"], s["quaternion"]))
        assert r.success, (r.kind, r.message)
        return {"duration": r.duration, "targets": list(r.targets), "end": self.joints()}

    def refusal(self, s):
        before = self.joints()
        r = self.move_to(self.pose(s["unreachable"], s["quaternion"]))
        assert not r.success
        assert r.duration == 0 and not r.targets
        after = self.joints()
        assert max(abs(a - b) for a, b in zip(before, after)) < 1e-9  # nothing moved
        return {"kind": r.kind, "message": r.message}

    def stop(self, s):
        """A trajectory without points on arm_controller/command stops what runs (docs/ros.md)."""
        from trajectory_msgs.msg import JointTrajectory
        command = self.rospy.Publisher("/arm_controller/command", JointTrajectory, queue_size=1)
        answered = threading.Event()

        def stop_soon():
            time.sleep(0.3)
            while not answered.is_set():  # until the node has it (a new publisher connects first)
                command.publish(JointTrajectory())
                answered.wait(0.05)

        stopper = threading.Thread(target=stop_soon)
        stopper.start()
        r = self.move_to(self.pose(s["position"], s["quaternion"]))
        answered.set()
        stopper.join()
        command.unregister()
        return {"stopped": not r.success and "stopped" in r.message, "message": r.message}


# ------------------------------------------------------------------------ the tests


@pytest.fixture(scope="module", autouse=True)
def ros_master():
    yield
    RosMaster.stop()


@pytest.fixture(scope="module", params=ARMS)
def arm_case(request, tmp_path_factory):
    arm_name = request.param
    folder = tmp_path_factory.mktemp(arm_name)
    return arm_name, scenario(arm_name), program_files(arm_name, folder)


def run_everywhere(arm_name, what, *args):
    """{app: what that app answered}, ROS in one node for the arm."""
    out = {}
    for app in ("cli", "python", "http"):
        runner = {"cli": Cli, "python": Python, "http": Http}[app](arm_name)
        out[app] = getattr(runner, what)(*args)
    if what != "program":
        with Ros(arm_name) as ros:
            out["ros"] = getattr(ros, what)(*args)
    return out


def test_a_ptp_to_a_pose_is_the_same_plan_and_end_in_every_app(arm_case):
    arm_name, s, _ = arm_case
    got = run_everywhere(arm_name, "ptp", s)
    reference = got["cli"]
    for app, r in got.items():
        assert abs(r["duration"] - reference["duration"]) <= DURATION_TOLERANCE, (app, r["duration"], reference["duration"])
        assert len(r["targets"]) == len(reference["targets"]), (app, r["targets"])
        for k, (a, b) in enumerate(zip(r["targets"], reference["targets"])):
            assert abs(a - b) <= TARGET_TOLERANCE, (app, "joint", k, a, b)
        for k, (end, target) in enumerate(zip(r["end"], r["targets"])):
            assert abs(end - target) <= max(ARRIVAL.values()), (app, "joint", k, "ended at", end, "target", target)


def test_an_unreachable_pose_is_refused_alike_in_every_app(arm_case):
    arm_name, s, _ = arm_case
    got = run_everywhere(arm_name, "refusal", s)
    reference = got["cli"]
    for app, r in got.items():
        assert r == reference, (app, r, "cli", reference)


def test_a_lin_run_with_a_zone_is_the_same_plan_in_every_app_that_runs_programs(arm_case):
    arm_name, _, (program, points) = arm_case
    got = run_everywhere(arm_name, "program", program, points)
    reference = got["cli"]
    for app, r in got.items():
        assert abs(r["duration"] - reference["duration"]) <= DURATION_TOLERANCE, (app, r, reference)


def test_a_stop_ends_a_move_in_every_app(arm_case):
    arm_name, s, _ = arm_case
    got = run_everywhere(arm_name, "stop", s)
    for app, r in got.items():
        assert r["stopped"], (app, r)
