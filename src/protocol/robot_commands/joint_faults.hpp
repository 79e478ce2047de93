// JointFaultRead, CMD 40: an armctl extension of Robot Commands, not in the xArm protocol
// (spec robot-commands.md does not list it). armctl's Mega arm controller answers it with
// one joint's fault state (docs/mega-controller.md "Joint faults"); an xArm board, the
// xArm emulator and the Linux daemon ignore it as an unknown CMD, as the spec decides. It
// is kept out of the spec's Request/BoardMessage variants on purpose: a board that decodes
// those must go on refusing CMD 40.
//
//   request:  55 55 03 28 servo
//   reply:    55 55 16 28 servo flags last_failure:u16 following_lost:u16 word0..word6:u16
#pragma once

#include <array>
#include <cstdint>

#include "core/error.hpp"
#include "protocol/robot_commands/frame.hpp"
#include "protocol/robot_commands/messages.hpp"

namespace armctl::rc {

constexpr std::uint8_t kJointFaultReadCmd = 40;
constexpr std::size_t kJointFaultReplyBytes = 20;

struct JointFaultReport {
  std::uint8_t servo = 0;
  bool answering = false;     // flags bit 0: the last transaction with the joint worked
  bool following = false;     // bit 1: its polled positions follow its plan
  bool words_read = false;    // bit 2: `words` were read since it stopped following
  bool behind_ramp = false;   // bit 3: the controller found it behind its setpoint ramp
                              // mid-move (a stall) and stopped that move
  std::uint16_t last_failure = 0;    // STATUS of its last failed transaction (990, 910, 940...); 0 none
  std::uint16_t following_lost = 0;  // times it stopped following (saturating)
  // read_diagnostic 0..6 (portable/joint_bus_codes.hpp): faults, bus events lost, encoder
  // edges lost, UART errors, reset cause, abandoned transactions, settings.
  std::array<std::uint16_t, 7> words{};
  bool operator==(const JointFaultReport&) const = default;
};

// The request for `servo`; refused (nothing to send) for a servo outside `servos`.
Result<Frame> encode_joint_fault_read(std::uint8_t servo, const ServoRange& servos);
// A CMD 40 frame from a board; an error naming what is wrong for any other frame.
Result<JointFaultReport> decode_joint_fault_reply(const Frame& frame);
// The reply a board sends (tests, emulators).
Frame encode_joint_fault_reply(const JointFaultReport& report);

}  // namespace armctl::rc
