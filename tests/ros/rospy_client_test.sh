#!/usr/bin/env bash
# A rospy client of the node as a user installs it (docs/ros.md "Writing a ROS client"):
# `cmake --install --component ros` into a temporary prefix, with a stand-in for the armctl
# Python module beside the message types (the two once clashed); a master on a free port, the
# installed node on the embedded xArm simulator, then tests/ros/rospy_client.py with
# Debian's python3. Everything it starts ends with it.
set -euo pipefail
build=$1
here=$(cd "$(dirname "$0")" && pwd)
prefix=$(mktemp -d /tmp/armctl-rospy-XXXXXX)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -TERM -- "-$p" 2>/dev/null || true; done
  for p in "${pids[@]}"; do wait "$p" 2>/dev/null || true; done
  rm -rf "$prefix"
}
trap cleanup EXIT
/usr/bin/python3 -c "import rospy, actionlib, rosservice" 2>/dev/null ||
  { echo "FAIL: rospy, actionlib or rosservice missing (Debian: python3-rospy python3-actionlib python3-rosservice)"; exit 1; }
cmake --install "$build" --component ros --prefix "$prefix" > "$prefix/install.log"
site=$(ls -d "$prefix"/lib/python3*/dist-packages)
[ -f "$site/armctl_msgs/srv/_SetGripper.py" ] || { echo "FAIL: armctl_msgs not installed in $site"; exit 1; }
[ -f "$site/control_msgs/msg/_FollowJointTrajectoryAction.py" ] || { echo "FAIL: control_msgs not installed"; exit 1; }
[ -f "$prefix/share/armctl_msgs/srv/SetGripper.srv" ] || { echo "FAIL: no SetGripper.srv in share/armctl_msgs"; exit 1; }
mkdir -p "$site/armctl" && echo '# stands in for the armctl Python module' > "$site/armctl/__init__.py"

port=$(/usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI="http://127.0.0.1:$port" ROS_HOSTNAME=127.0.0.1 ROS_HOME="$prefix/ros" ROS_LOG_DIR="$prefix/ros/log"
export PYTHONPATH="$site${PYTHONPATH:+:$PYTHONPATH}" ASAN_OPTIONS=detect_leaks=0
setsid rosmaster --core -p "$port" > "$prefix/master.log" 2>&1 & pids+=($!)
setsid "$prefix/bin/armctl_ros" _arm:=xarm __name:=armctl_ros > "$prefix/node.log" 2>&1 & pids+=($!)
if ! timeout 120 /usr/bin/python3 "$here/rospy_client.py"; then
  echo "--- node log:"; tail -n 30 "$prefix/node.log"
  echo "--- master log:"; tail -n 10 "$prefix/master.log"
  exit 1
fi
