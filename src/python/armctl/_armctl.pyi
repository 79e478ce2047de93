"""Type stubs of armctl's native module (src/python/*.cpp). Units are SI: rad, m, s."""

from typing import Any, Dict, Literal, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

Vector = Sequence[float] | npt.NDArray[np.float64]
JointKey = Union[str, int]
# One value per joint (None keeps it), or {joint name or index: value}.
Targets = Union[Sequence[Optional[float]], npt.NDArray[np.float64], Mapping[JointKey, Optional[float]]]
__version__: str  # the project version, as `armctl --version` prints it

ErrorKindName = Literal["invalid_argument", "invalid_config", "io", "timeout", "protocol", "device", "unsupported"]

class Error(RuntimeError):
    """Every failure armctl reports; ``kind`` is armctl's error kind, ``message`` the message,
    ``detail`` what more it carries (None, or the name of a typed detail whose fields follow)."""

    kind: ErrorKindName
    message: str
    detail: Optional[Literal["following_error", "path_refusal", "collision", "limit", "source_place", "device_lost"]]
    # following_error: joint, measured, planned, limit; path_refusal: segment (0-based),
    # fraction, point (m), joint; collision: bodies, depth (m), fraction, point (the tool point,
    # m); limit (the fence, a reduced joint range): the same fields, bodies = (what breaks it,
    # the limit), broken_limit "fence" | "joint range"; source_place: file, line, column.
    joint: Optional[str]
    measured: float
    planned: float
    limit: float
    segment: int
    fraction: Optional[float]
    point: Optional[Tuple[float, float, float]]
    bodies: Tuple[str, str]
    depth: float
    broken_limit: Optional[Literal["fence", "joint range"]]
    file: str
    line: int
    column: int

class JointState:
    """Every joint's position as read."""

    @property
    def time(self) -> float:
        """s on the device's clock, when the positions were read"""
    @property
    def positions(self) -> npt.NDArray[np.float64]:
        """every joint, rad (revolute) or m (prismatic), in the model's order"""
    @property
    def device(self) -> npt.NDArray[np.float64]:
        """the same in device units, as read (servo units, clicks)"""

class Pose:
    """A tool pose in the base frame."""

    @property
    def position(self) -> npt.NDArray[np.float64]:
        """x, y, z in m"""
    @property
    def orientation(self) -> npt.NDArray[np.float64]:
        """unit quaternion w, x, y, z"""
    @property
    def roll(self) -> float: ...
    @property
    def pitch(self) -> float: ...
    @property
    def yaw(self) -> float:
        """rad; on the xArm, where the arm points"""

class IkSolution:
    """One inverse-kinematics solution."""

    @property
    def joints(self) -> npt.NDArray[np.float64]:
        """chain joints, SI, base to tool"""
    @property
    def elbow(self) -> Optional[Literal["left", "right", "up", "down"]]: ...
    @property
    def wrist_flipped(self) -> Optional[bool]: ...
    @property
    def reaching_back(self) -> Optional[bool]: ...

class Joint:
    """One joint of the arm model."""

    @property
    def name(self) -> str: ...
    @property
    def kind(self) -> Literal["revolute", "prismatic"]: ...
    @property
    def role(self) -> Literal["chain", "gripper"]: ...
    @property
    def lower(self) -> float: ...
    @property
    def upper(self) -> float: ...
    @property
    def velocity(self) -> float: ...
    @property
    def acceleration(self) -> float: ...
    @property
    def jerk(self) -> float: ...
    @property
    def robot_commands_id(self) -> Optional[int]: ...
    @property
    def joint_bus_id(self) -> Optional[int]: ...

class PlannedMove:
    """What move_joints, move_to and gripper planned: as every armctl app answers a move."""

    @property
    def duration(self) -> float: ...
    @property
    def targets(self) -> npt.NDArray[np.float64]: ...
    @property
    def note(self) -> str: ...

class MotionReport:
    """How a streamed motion (joint_move, move_linear, path) went."""

    @property
    def elapsed(self) -> float: ...
    @property
    def t_reached(self) -> float: ...
    @property
    def duration(self) -> float: ...
    @property
    def completed(self) -> bool: ...
    @property
    def stopped(self) -> bool:
        """Stopped on the path by stop() from another thread (Ctrl-C and close() raise instead)."""
    @property
    def points(self) -> int: ...
    @property
    def reads(self) -> int: ...
    @property
    def period(self) -> float: ...
    @property
    def largest_following_error(self) -> float: ...
    @property
    def largest_following_joint(self) -> Optional[str]: ...
    @property
    def held(self) -> float: ...

class Segment:
    """A Cartesian path segment, made by Lin or Circ."""

    @property
    def kind(self) -> Literal["LIN", "CIRC"]: ...
    @property
    def position(self) -> npt.NDArray[np.float64]: ...
    @property
    def via(self) -> npt.NDArray[np.float64]: ...
    @property
    def roll(self) -> Optional[float]: ...
    @property
    def pitch(self) -> Optional[float]: ...
    @property
    def yaw(self) -> Optional[float]: ...
    @property
    def speed(self) -> float: ...
    @property
    def angular_speed(self) -> float: ...
    @property
    def zone(self) -> float: ...

def Lin(position: Vector, roll: Optional[float] = None, pitch: Optional[float] = None, yaw: Optional[float] = None,
        speed: float = 0.05, angular_speed: float = 0.7853981633974483, zone: float = 0.0) -> Segment:
    """A straight line of the tool to ``position`` (m) at ``speed`` m/s; ``zone`` (m) blends its end corner."""

def Circ(via: Vector, position: Vector, roll: Optional[float] = None, pitch: Optional[float] = None,
         yaw: Optional[float] = None, speed: float = 0.05, angular_speed: float = 0.7853981633974483,
         zone: float = 0.0) -> Segment:
    """A circular arc of the tool through ``via`` to ``position`` (m)."""

class Servo:
    """A servo session (Arm.servo()), for a with block: the arm follows the commands sent, each
    replacing the last, and slows to rest when they stop for ``timeout`` s or the block ends."""

    def __enter__(self) -> "Servo": ...
    def __exit__(self, *exc: object) -> None: ...
    def twist(self, linear: Vector = ..., angular: Vector = ..., frame: Literal["base", "tool"] = "base") -> None:
        """The tool at ``linear`` m/s, turning at ``angular`` rad/s (x, y, z) in the base or tool frame."""
    def joint_velocities(self, values: Sequence[float]) -> None:
        """Every joint's velocity (rad/s or m/s, the model's order; the gripper's is ignored)."""
    def joint_targets(self, values: Sequence[Optional[float]]) -> None:
        """Where the joints should go (SI; None keeps one still); beyond a limit: to the limit."""
    def pose_target(self, position: Vector, roll: Optional[float] = None, pitch: Optional[float] = None,
                    yaw: Optional[float] = None) -> None:
        """Where the tool should go (m; rad), by the nearest IK solution."""
    def gripper(self, closed_fraction: float) -> None:
        """The gripper to 0 = open .. 1 = closed (the arm still)."""
    def stop(self) -> None:
        """The arm slows to rest and holds; the session goes on."""
    @property
    def status(self) -> Dict[str, Any]:
        """The last cycle: positions, velocities, scale, slowdown, detail, commanded, at_rest, commands, elapsed."""

class Calibration:
    """The guided calibration's steps (docs/calibration.md), made by Arm.calibration(). ``joint``:
    an index (0-based, the model's order) or a name. Results are plain dicts (the HTTP API's fields);
    every failure raises armctl.Error. Nothing is written until confirm()."""

    def __enter__(self) -> Calibration: ...
    def __exit__(self, *exc: Any) -> None: ...
    @property
    def joint_names(self) -> list[str]: ...
    def find(self) -> Dict[str, Any]:
        """Step 1: {'devices': [{'id', 'joint', 'index', 'answers', 'position'}], 'silent': [ids], 'text'}."""
    def set_servo_id(self, id: int) -> None:
        """Step 1 on the xArm: gives the ONE servo connected the ID (unplug the others first)."""
    def wiggle(self, joint: JointKey) -> None:
        """Step 2: moves the joint a little and back."""
    def answer_which(self, joint: JointKey, moved: JointKey) -> None:
        """Step 2's answer; armctl.Error naming both joints when another one moved."""
    def nudge(self, joint: JointKey) -> None:
        """Step 3: moves the joint a little in its positive direction."""
    def answer_direction(self, joint: JointKey, went_as_shown: bool) -> None:
        """Step 3's answer: False flips the joint (pending)."""
    def release(self) -> None:
        """Torque off: the joints move by hand."""
    def hold(self) -> None:
        """Torque on where the arm stands."""
    def read_joint(self, joint: JointKey) -> float:
        """The joint's value now as the arm file reads it before the pending changes."""
    def mark_of(self, joint: JointKey) -> float:
        """Where the joint stands for its zero step."""
    def zero_here(self, joint: JointKey, mark: Optional[float] = None) -> Dict[str, Any]:
        """Step 4: {'kind': 'file_zero'|'servo_offset', 'shift', 'servo_offset', 'text'}."""
    def limits(self, joint: JointKey, end_a: float, end_b: float) -> Dict[str, float]:
        """Step 5: {'lower', 'upper'} in the new readings."""
    def gripper(self, open: float, closed: float) -> Dict[str, float]:
        """Step 6: {'open', 'closed'} in the new readings."""
    def sheet_points(self) -> list[Dict[str, Any]]:
        """Step 7: the printed sheet's marks, [{'name', 'position': [x, y, z]}] (m)."""
    def touch(self, name: str, position: Sequence[float]) -> Dict[str, Any]:
        """Step 7: the tool stands on `name` at `position` (m): {'name', 'position', 'joints'}."""
    def verify(self) -> Dict[str, Any]:
        """Step 7: {'points': [{'name', 'error', 'distance'}], 'rms', 'max', 'worst'} (m)."""
    def fit(self) -> Dict[str, Any]:
        """Step 8: {'estimates', 'before', 'after', 'condition', 'iterations'}."""
    def forget(self, joint: Optional[JointKey] = None) -> None:
        """Forgets one joint's pending answers, or all."""
    def changes(self) -> Dict[str, Any]:
        """{'joints': [{'joint', 'flip', 'zero_shift', 'limits'}], 'servo_offsets', 'gripper', 'link_lengths', 'empty'}."""
    def describe(self) -> str:
        """The pending changes for people."""
    def confirm(self) -> Dict[str, str]:
        """Writes them: {'file', 'previous'}."""

class Arm:
    """One arm in SI units over any device: Arm(arm='xarm', device='') ('' = the embedded simulator).

    Safe to share between threads: calls take turns on the device, one at a time."""

    def __init__(self, arm: str = "xarm", device: str = "", scene: str = "") -> None: ...
    @property
    def scene(self) -> Optional[str]:
        """The scene file (docs/scene.md) every motion is checked against before it starts, or None
        (the arm's own links only)."""
    @scene.setter
    def scene(self, file: Optional[str]) -> None:
        """Loads a scene file (a bad one raises Error and keeps the old scene); None clears it."""
    @property
    def fence(self) -> Optional[bool]:
        """Whether the scene's fence is on, or None when the scene sets none (docs/scene.md)."""
    @fence.setter
    def fence(self, on: bool) -> None:
        """Switches the scene's fence on or off (without one: raises Error)."""
    @property
    def reduced_mode(self) -> Optional[bool]:
        """Whether the scene's reduced mode (tool speed cap, joint ranges) is on, or None when the scene sets none."""
    @reduced_mode.setter
    def reduced_mode(self, on: bool) -> None:
        """Switches the scene's reduced mode on or off (without one: raises Error)."""
    def close(self) -> None:
        """Stops what another thread runs on the arm (a wait, a streamed motion: it raises Error), waits
        for it, then closes the device; later calls raise Error."""
    def __enter__(self) -> "Arm": ...
    def __exit__(self, *exc: object) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def joints(self) -> list[Joint]: ...
    @property
    def joint_names(self) -> list[str]: ...
    @property
    def chain_joints(self) -> int: ...
    @property
    def protocol(self) -> Literal["robot_commands", "joint_bus"]: ...
    @property
    def device_description(self) -> str: ...
    def read(self) -> JointState:
        """Every joint's position now."""
    def pose(self) -> Pose:
        """The tool pose where the arm stands now."""
    def forward(self, q: Vector) -> Pose:
        """The tool pose at chain joints ``q`` (or every joint); nothing is sent. A value that is not finite
        or past its joint's limits raises Error naming the joint, the value and the range."""
    def inverse(self, position: Vector, roll: Optional[float] = None, pitch: Optional[float] = None,
                yaw: Optional[float] = None, elbow: Optional[str] = None, nearest_orientation: bool = False,
                near: Optional[Vector] = None) -> list[IkSolution]:
        """Every IK solution for the tool at ``position`` (m), nearest to ``near`` (default: read()) first."""
    def move_joints(self, targets: Targets, duration: Optional[float] = None, speed: float = 0.25,
                    wait: bool = False, timeout: float = 10.0) -> PlannedMove:
        """Moves the joints that have a target; all arrive together (after ``duration`` s, or at ``speed``)."""
    def move_to(self, position: Vector, roll: Optional[float] = None, pitch: Optional[float] = None,
                yaw: Optional[float] = None, elbow: Optional[str] = None, nearest_orientation: bool = False,
                duration: Optional[float] = None, speed: float = 0.25, wait: bool = False,
                timeout: float = 10.0, avoid: bool = False, avoid_time: float = 1.0) -> PlannedMove:
        """PTP: the tool to ``position`` (m) through the IK solution nearest the current joints;
        ``avoid=True``: around obstacles when the direct move would collide (within ``avoid_time`` s)."""
    def move_linear(self, position: Vector, roll: Optional[float] = None, pitch: Optional[float] = None,
                    yaw: Optional[float] = None, speed: float = 0.05, angular_speed: float = 0.7853981633974483,
                    speed_override: float = 1.0) -> MotionReport:
        """LIN: the tool along a straight line, streamed; returns when it is there."""
    def path(self, segments: Sequence[Segment], speed_override: float = 1.0, acceleration: float = 0.5,
             angular_acceleration: float = 3.0) -> MotionReport:
        """Runs a Cartesian path of Lin and Circ segments, checked as a whole first."""
    def check_program(self, file: str, points: str = "") -> Dict[str, Any]:
        """Checks a robot program before anything moves: {'duration', 'moves', 'pieces'}."""
    def run_program(self, file: str, points: str = "", speed_override: float = 1.0) -> Dict[str, Any]:
        """Checks, then runs a robot program: {'completed', 'pieces', 'elapsed', 'largest_following_error', 'printed'}."""
    def joint_move(self, target: Targets, waypoints: Sequence[Targets] = ..., speed: float = 0.25,
                   min_duration: float = 0.0, speed_override: float = 1.0) -> MotionReport:
        """A jerk-limited joint move through ``waypoints`` to ``target``, streamed."""
    def servo(self, speed: float = 1.0, timeout: float = 0.2, max_linear_speed: float = 0.25,
              max_angular_speed: float = 1.5) -> Servo:
        """A servo session for a with block (docs/servo.md): twists, joint velocities and targets followed
        as they come, within every limit; the arm's other calls wait until the block ends."""
    def wait(self, timeout: float = 10.0, poll: Optional[float] = None, angle_tolerance: float = 0.0087,
             length_tolerance: float = 0.0005) -> JointState:
        """Until every joint of the last move is there and at rest; Error (timeout) names the late joints."""
    def stop(self) -> None:
        """Stops every joint where it is and holds it; what other threads run on the arm stops first."""
    def calibration(self, servo_offsets: bool = True) -> Calibration:
        """The guided calibration (docs/calibration.md "Python") for a with block: nothing is written
        until confirm(); leaving the block without it writes nothing."""
    def set_torque(self, on: bool) -> None:
        """off: the arm can be moved by hand; on: hold where it stands."""
    def health(self) -> Dict[str, Any]:
        """The supply and the joints' faults, as `armctl arm health` and the dashboard show them:
        {'battery_volts': float or None, 'faults': [str]}."""
    def clear_faults(self) -> None:
        """Clears the faults the joints hold (fix the cause first): each holds where it is and drives
        again. Error (device) names the joints that could not be cleared; nothing to clear on an xArm."""
    def gripper(self, closed_fraction: float, duration: Optional[float] = None, speed: float = 0.5,
                wait: bool = False, timeout: float = 10.0) -> PlannedMove:
        """0 = open, 1 = closed."""
    def download_group(self, group: int, text: str) -> None:
        """Downloads an action group in armctl's group-file format (Robot Commands devices)."""
    def run_group(self, group: int, times: int = 1) -> None:
        """Runs a stored action group ``times`` times (0: until stop_group)."""
    def stop_group(self) -> None: ...
    def erase_group(self, group: int) -> None: ...
    def group_events(self, timeout: float = 0.0) -> list[dict[str, Optional[Union[str, int]]]]:
        """Action-group notifications: {'kind', 'group', 'count'}."""

class RobotCommands:
    """A Robot Commands board in device units: RobotCommands(device='sim', servo_count=6, timeout=0).

    Safe to share between threads: each request and its reply take their turn on the link."""

    def __init__(self, device: str = "sim", servo_count: int = 6, timeout: float = 0.0) -> None: ...
    def close(self) -> None:
        """Waits for the call another thread runs (group_events ends early), then closes the board."""
    def __enter__(self) -> "RobotCommands": ...
    def __exit__(self, *exc: object) -> None: ...
    @property
    def servo_count(self) -> int: ...
    def move(self, targets: Sequence[tuple[int, Optional[int]]], time_ms: int) -> None:
        """[(servo, position 0..1000 or None), ...] over time_ms."""
    def read_positions(self, servos: Optional[Sequence[int]] = None) -> list[tuple[int, int]]: ...
    def servos_off(self, servos: Optional[Sequence[int]] = None) -> None: ...
    def battery_millivolts(self) -> int: ...
    def read_offsets(self, servos: Optional[Sequence[int]] = None) -> list[tuple[int, int]]: ...
    def adjust_offset(self, servo: int, offset: int) -> None: ...
    def save_offsets(self, servos: Optional[Sequence[int]] = None) -> None: ...
    def write_servo_id(self, new_id: int) -> None: ...
    def download_group(self, group: int, text: str) -> None: ...
    def run_group(self, group: int, times: int = 1) -> None: ...
    def stop_group(self) -> None: ...
    def erase_group(self, group: int) -> None: ...
    def set_group_speed(self, group: int, percent: int) -> None: ...
    def group_events(self, timeout: float = 0.0) -> list[dict[str, Optional[Union[str, int]]]]: ...
