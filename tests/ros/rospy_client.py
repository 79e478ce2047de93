"""A rospy client of the installed armctl_ros node, as docs/ros.md "Writing a ROS client" shows:
the node's services through armctl_msgs, a FollowJointTrajectory goal through control_msgs and
actionlib, joint_states, and `rosservice`'s own lookup of a service's type (which imports
<package>.srv: it failed when the services were in a package named like the armctl module).
Run by rospy_client_test.sh against a running node; exits non-zero with a message on failure."""
import sys

import actionlib
import rosservice
import rospy
from armctl_msgs.srv import SetGripper
from control_msgs.msg import FollowJointTrajectoryAction, FollowJointTrajectoryGoal, FollowJointTrajectoryResult
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectoryPoint


def fail(what):
    print(f"FAIL: {what}")
    sys.exit(1)


def joint_state(timeout=10.0):
    return rospy.wait_for_message("/joint_states", JointState, timeout=timeout)


def main():
    rospy.init_node("armctl_rospy_client_test", anonymous=True)

    # The type of a service as `rosservice call` finds it, armctl's Python module installed beside.
    for name, expected in (("/armctl_ros/gripper", "armctl_msgs/SetGripper"),
                           ("/armctl_ros/run_action_group", "armctl_msgs/RunActionGroup")):
        rospy.wait_for_service(name, timeout=30)
        if rosservice.get_service_type(name) != expected:
            fail(f"{name} is of type {rosservice.get_service_type(name)}, expected {expected}")
        cls = rosservice.get_service_class_by_name(name)
        if cls._type != expected:
            fail(f"rosservice found {cls._type} for {name}")

    gripper = rospy.ServiceProxy("/armctl_ros/gripper", SetGripper)
    answer = gripper(closed_fraction=0.5)
    if not answer.success:
        fail(f"gripper 0.5: {answer.message}")
    refused = gripper(closed_fraction=2.0)
    if refused.success or "closed_fraction" not in refused.message and "0..1" not in refused.message:
        fail(f"gripper 2.0 was not refused with a message: {refused.success} {refused.message!r}")

    now = joint_state()
    names = list(now.name)
    chain = [n for n in names if n != "servo1"]  # the xArm's gripper may be left out
    start = [now.position[names.index(n)] for n in chain]
    target = [p + (0.2 if i == 0 else 0.0) for i, p in enumerate(start)]

    client = actionlib.SimpleActionClient("/arm_controller/follow_joint_trajectory", FollowJointTrajectoryAction)
    if not client.wait_for_server(rospy.Duration(30)):
        fail("no FollowJointTrajectory server")
    goal = FollowJointTrajectoryGoal()
    goal.trajectory.joint_names = chain
    point = JointTrajectoryPoint()
    point.positions = target
    point.velocities = [0.0] * len(chain)
    point.time_from_start = rospy.Duration(1.5)
    goal.trajectory.points = [point]
    client.send_goal(goal)
    if not client.wait_for_result(rospy.Duration(30)):
        fail("the trajectory did not end within 30 s")
    result = client.get_result()
    if result.error_code != FollowJointTrajectoryResult.SUCCESSFUL:
        fail(f"the trajectory ended with {result.error_code}: {result.error_string}")
    after = joint_state()
    reached = after.position[list(after.name).index(chain[0])]
    if abs(reached - target[0]) > 0.02:
        fail(f"{chain[0]} at {reached:.4f} rad, asked {target[0]:.4f}")

    # A goal beyond the limits is rejected with its error code and a message, and nothing moves.
    # (A client of its own: actionlib's simple client complains about the finished goal's
    # status messages once it tracks another.)
    second = actionlib.SimpleActionClient("/arm_controller/follow_joint_trajectory", FollowJointTrajectoryAction)
    second.wait_for_server(rospy.Duration(30))
    goal.trajectory.points[0].positions = [10.0] + target[1:]
    second.send_goal(goal)
    second.wait_for_result(rospy.Duration(10))
    bad = second.get_result()
    if bad is None or bad.error_code != FollowJointTrajectoryResult.INVALID_GOAL or not bad.error_string:
        fail(f"a goal at 10 rad was not refused as INVALID_GOAL: {bad}")
    still = joint_state().position[list(after.name).index(chain[0])]
    if abs(still - reached) > 0.01:
        fail(f"{chain[0]} moved from {reached:.4f} to {still:.4f} rad after a refused goal")
    print("rospy client: ok (services, rosservice lookup, FollowJointTrajectory, joint_states, a refusal)")


if __name__ == "__main__":
    main()
