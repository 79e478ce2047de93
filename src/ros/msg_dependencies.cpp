// Build tool: writes the .msg definitions of the installed messages that the local
// FollowJointTrajectory action and the node's services use (trajectory_msgs,
// std_msgs/Header, actionlib_msgs, geometry_msgs/Pose), as
// <out>/<package>/<Name>.msg, for genmsg/gencpp. Debian's message packages carry no .msg
// files, only the generated headers, whose full definition text (every nested type after
// a separator line) this reads back: the same text the MD5 sums were computed from.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <actionlib_msgs/GoalStatusArray.h>
#include <geometry_msgs/Pose.h>
#include <trajectory_msgs/JointTrajectory.h>

namespace {

namespace fs = std::filesystem;

bool write_msg(const fs::path& out, const std::string& type, const std::string& text) {
  const auto slash = type.find('/');
  if (slash == std::string::npos) return false;
  const fs::path dir = out / type.substr(0, slash);
  fs::create_directories(dir);
  std::ofstream f(dir / (type.substr(slash + 1) + ".msg"));
  f << text;
  return bool(f);
}

// The definition of M and of every type nested in it.
template <typename M>
bool dump(const fs::path& out) {
  const std::string text = ros::message_traits::Definition<M>::value();
  const std::string separator =
      "\n================================================================================\nMSG: ";
  std::size_t at = text.find(separator);
  if (!write_msg(out, ros::message_traits::DataType<M>::value(), text.substr(0, at))) return false;
  while (at != std::string::npos) {
    const std::size_t name = at + separator.size(), eol = text.find('\n', name);
    if (eol == std::string::npos) return false;
    const std::size_t next = text.find(separator, eol);
    const std::string body = text.substr(eol + 1, next == std::string::npos ? std::string::npos : next - eol - 1);
    if (!write_msg(out, text.substr(name, eol - name), body)) return false;
    at = next;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIR\n", argv[0]);
    return 2;
  }
  if (!dump<trajectory_msgs::JointTrajectory>(argv[1]) || !dump<actionlib_msgs::GoalStatus>(argv[1]) ||
      !dump<geometry_msgs::Pose>(argv[1])) {
    std::fprintf(stderr, "%s: cannot write the message definitions into %s\n", argv[0], argv[1]);
    return 1;
  }
  return 0;
}
