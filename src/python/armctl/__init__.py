"""armctl: drive, simulate and program the xArm and the SCARA arm from Python.

    import armctl
    arm = armctl.Arm()                     # the xArm, on an emulated board inside this process
    print(arm.pose())                      # the tool pose, m and rad
    arm.move_to([0.15, 0.05, 0.12], wait=True)
    arm.move_linear([0.18, 0.04, 0.10], speed=0.04)

armctl.Arm is the Arm API in SI units on any device URI; armctl.RobotCommands speaks to a Robot
Commands board in device units; ``import armctl.xarm as xarm`` runs scripts written for the
``xarm`` package. Every failure raises armctl.Error (a RuntimeError with .kind and .message).
Docs: docs/python.md.
"""

from ._armctl import (  # noqa: F401  (the package's API)
    Arm,
    Calibration,
    Circ,
    Error,
    IkSolution,
    Joint,
    JointState,
    Lin,
    MotionReport,
    PlannedMove,
    Pose,
    RobotCommands,
    Segment,
    Servo,
    __version__,
)

__all__ = [
    "Arm",
    "Calibration",
    "Circ",
    "Error",
    "IkSolution",
    "Joint",
    "JointState",
    "Lin",
    "MotionReport",
    "PlannedMove",
    "Pose",
    "RobotCommands",
    "Segment",
    "Servo",
]
