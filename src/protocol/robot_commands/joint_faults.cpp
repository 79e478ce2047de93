#include "protocol/robot_commands/joint_faults.hpp"

#include <fmt/core.h>

#include "portable/joint_bus_codes.hpp"
#include "protocol/robot_commands/wire_bytes.hpp"

namespace armctl::rc {
namespace {
constexpr std::uint8_t kAnswering = 1, kFollowing = 2, kWordsRead = 4, kBehindRamp = 8;
constexpr std::uint8_t kKnownFlags = kAnswering | kFollowing | kWordsRead | kBehindRamp;

// Both extensions' requests: CMD and the one servo byte.
Result<Frame> servo_request(std::uint8_t cmd, const char* name, std::uint8_t servo, const ServoRange& servos) {
  if (!servos.contains(servo))
    return Error{ErrorKind::invalid_argument, fmt::format("{}: servo {} is not on this board (allowed {}..{})", name,
                                                          servo, servos.first, servos.last)};
  return Frame{cmd, {servo}};
}

// Both replies: the CMD expected and exactly `bytes` of DATA.
Status check_reply(const Frame& f, std::uint8_t cmd, std::size_t bytes, const char* name) {
  if (f.cmd != cmd)
    return Error{ErrorKind::protocol, fmt::format("{} reply: CMD {} (expected {})", name, f.cmd, cmd)};
  if (f.data.size() != bytes)
    return Error{ErrorKind::protocol, fmt::format("{} reply: {} bytes of DATA (expected {}): {}", name,
                                                  f.data.size(), bytes, to_hex(f.data))};
  return Ok{};
}
}  // namespace

Result<Frame> encode_joint_fault_read(std::uint8_t servo, const ServoRange& servos) {
  return servo_request(kJointFaultReadCmd, "JointFaultRead", servo, servos);
}

Result<JointFaultReport> decode_joint_fault_reply(const Frame& f) {
  if (auto ok = check_reply(f, kJointFaultReadCmd, kJointFaultReplyBytes, "JointFaultRead"); !ok) return ok.error();
  wire::Reader r(f.data);
  JointFaultReport out;
  out.servo = r.u8();
  const std::uint8_t flags = r.u8();
  if ((flags & ~kKnownFlags) != 0)
    return Error{ErrorKind::protocol,
                 fmt::format("JointFaultRead reply: flags 0x{:02X} has bits this SDK does not know", flags)};
  out.answering = (flags & kAnswering) != 0;
  out.following = (flags & kFollowing) != 0;
  out.words_read = (flags & kWordsRead) != 0;
  out.behind_ramp = (flags & kBehindRamp) != 0;
  out.last_failure = r.u16();
  out.following_lost = r.u16();
  for (auto& w : out.words) w = r.u16();
  return out;
}

Frame encode_joint_fault_reply(const JointFaultReport& report) {
  Frame f{kJointFaultReadCmd, {}};
  wire::put_u8(f.data, report.servo);
  wire::put_u8(f.data, static_cast<std::uint8_t>((report.answering ? kAnswering : 0) |
                                                 (report.following ? kFollowing : 0) |
                                                 (report.words_read ? kWordsRead : 0) |
                                                 (report.behind_ramp ? kBehindRamp : 0)));
  wire::put_u16(f.data, report.last_failure);
  wire::put_u16(f.data, report.following_lost);
  for (auto w : report.words) wire::put_u16(f.data, w);
  return f;
}

bool JointFaultClearReply::cleared() const {
  return status == static_cast<std::uint16_t>(joint_bus::success_status(joint_bus::cmd_clear_faults));
}

Result<Frame> encode_joint_fault_clear(std::uint8_t servo, const ServoRange& servos) {
  return servo_request(kJointFaultClearCmd, "JointFaultClear", servo, servos);
}

Result<JointFaultClearReply> decode_joint_fault_clear_reply(const Frame& f) {
  if (auto ok = check_reply(f, kJointFaultClearCmd, kJointFaultClearReplyBytes, "JointFaultClear"); !ok)
    return ok.error();
  wire::Reader r(f.data);
  JointFaultClearReply out;
  out.servo = r.u8();
  out.status = r.u16();
  return out;
}

Frame encode_joint_fault_clear_reply(const JointFaultClearReply& reply) {
  Frame f{kJointFaultClearCmd, {}};
  wire::put_u8(f.data, reply.servo);
  wire::put_u16(f.data, reply.status);
  return f;
}

}  // namespace armctl::rc
