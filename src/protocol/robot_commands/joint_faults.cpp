#include "protocol/robot_commands/joint_faults.hpp"

#include <fmt/core.h>

#include "portable/joint_bus_codes.hpp"
#include "protocol/robot_commands/wire_bytes.hpp"

namespace armctl::rc {
namespace {
constexpr std::uint8_t kAnswering = 1, kFollowing = 2, kWordsRead = 4, kBehindRamp = 8;
constexpr std::uint8_t kKnownFlags = kAnswering | kFollowing | kWordsRead | kBehindRamp;
}  // namespace

Result<Frame> encode_joint_fault_read(std::uint8_t servo, const ServoRange& servos) {
  if (!servos.contains(servo))
    return Error{ErrorKind::invalid_argument,
                 fmt::format("JointFaultRead: servo {} is not on this board (allowed {}..{})", servo,
                             servos.first, servos.last)};
  return Frame{kJointFaultReadCmd, {servo}};
}

Result<JointFaultReport> decode_joint_fault_reply(const Frame& f) {
  if (f.cmd != kJointFaultReadCmd)
    return Error{ErrorKind::protocol, fmt::format("JointFaultRead reply: CMD {} (expected {})", f.cmd,
                                                  kJointFaultReadCmd)};
  if (f.data.size() != kJointFaultReplyBytes)
    return Error{ErrorKind::protocol,
                 fmt::format("JointFaultRead reply: {} bytes of DATA (expected {}): {}", f.data.size(),
                             kJointFaultReplyBytes, to_hex(f.data))};
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
  if (!servos.contains(servo))
    return Error{ErrorKind::invalid_argument,
                 fmt::format("JointFaultClear: servo {} is not on this board (allowed {}..{})", servo,
                             servos.first, servos.last)};
  return Frame{kJointFaultClearCmd, {servo}};
}

Result<JointFaultClearReply> decode_joint_fault_clear_reply(const Frame& f) {
  if (f.cmd != kJointFaultClearCmd)
    return Error{ErrorKind::protocol, fmt::format("JointFaultClear reply: CMD {} (expected {})", f.cmd,
                                                  kJointFaultClearCmd)};
  if (f.data.size() != kJointFaultClearReplyBytes)
    return Error{ErrorKind::protocol,
                 fmt::format("JointFaultClear reply: {} bytes of DATA (expected {}): {}", f.data.size(),
                             kJointFaultClearReplyBytes, to_hex(f.data))};
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
