#!/usr/bin/env bash
# The installed ROS package (docs/ros.md "Install"): `cmake --install --component ros` into a
# temporary prefix, then roslaunch finds the package on ROS_PACKAGE_PATH, resolves the node
# of each launch file to <prefix>/share/armctl/nodes/armctl_ros and passes the arguments on
# as the node's parameters. Nothing is started (no master needed).
set -euo pipefail
build=$1
prefix=$(mktemp -d /tmp/armctl-ros-launch-XXXXXX)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --component ros --prefix "$prefix" > "$prefix/install.log"
export ROS_PACKAGE_PATH="$prefix/share:/usr/share" ROS_HOME="$prefix/ros" ROS_LOG_DIR="$prefix/ros/log"
fail() { echo "FAIL: $*"; exit 1; }
for arm in xarm scara; do
  args=$(roslaunch --args /armctl_ros armctl "$arm.launch" device:=hid)
  [[ "$args" == *"$prefix/share/armctl/nodes/armctl_ros __name:=armctl_ros"* ]] || fail "$arm: node command line: $args"
  [ -x "$prefix/share/armctl/nodes/armctl_ros" ] || fail "$arm: the node is not executable"
  params=$(roslaunch --dump-params armctl "$arm.launch" device:=hid)
  grep -qx "/armctl_ros/arm: $arm" <<<"$params" || fail "$arm: arm parameter: $params"
  grep -qx "/armctl_ros/device: hid" <<<"$params" || fail "$arm: device parameter: $params"
  # A device URI that looks like a number stays a string.
  params=$(roslaunch --dump-params armctl "$arm.launch" device:=5)
  grep -qx "/armctl_ros/device: '5'" <<<"$params" || fail "$arm: device 5 is not a string: $params"
  nodes=$(roslaunch --nodes armctl "$arm.launch")
  grep -qx "/robot_state_publisher" <<<"$nodes" || fail "$arm: no robot_state_publisher: $nodes"
  grep -q "/rviz" <<<"$(roslaunch --nodes armctl "$arm.launch" rviz:=true)" || fail "$arm: rviz:=true adds no rviz"
  [ -f "$prefix/share/armctl/rviz/armctl.rviz" ] || fail "no rviz configuration"
done
echo "launch files: ok"
