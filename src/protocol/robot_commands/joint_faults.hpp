// JointFaultRead, CMD 40, and JointFaultClear, CMD 41: armctl extensions of Robot
// Commands, not in the xArm protocol (spec robot-commands.md does not list them). armctl's
// arm controllers (the Mega and the Linux daemon) answer them (docs/mega-controller.md
// "Joint faults"): one joint's fault state, and clear_faults sent to one joint; an xArm
// board and the xArm emulator ignore them as unknown CMDs, as the spec decides. They are kept out of
// the spec's Request/BoardMessage variants on purpose: a board that decodes those must go
// on refusing CMD 40 and 41.
//
//   read request:   55 55 03 28 servo
//   read reply:     55 55 16 28 servo flags last_failure:u16 following_lost:u16 word0..word6:u16
//   clear request:  55 55 03 29 servo
//   clear reply:    55 55 05 29 servo status:u16   (once the joint answered; 510 + 41 = cleared)
#pragma once

#include <array>
#include <cstdint>

#include "core/error.hpp"
#include "protocol/robot_commands/frame.hpp"
#include "protocol/robot_commands/messages.hpp"

namespace armctl::rc {

constexpr std::uint8_t kJointFaultReadCmd = 40;
constexpr std::size_t kJointFaultReplyBytes = 20;
constexpr std::uint8_t kJointFaultClearCmd = 41;
constexpr std::size_t kJointFaultClearReplyBytes = 3;

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

// What a joint answered to the clear_faults the board sent it: the joint bus STATUS word
// (joint-bus.md: 510 + 41 when it cleared; 990 no answer, 910 wrong joint, ...).
struct JointFaultClearReply {
  std::uint8_t servo = 0;
  std::uint16_t status = 0;
  bool cleared() const;
  bool operator==(const JointFaultClearReply&) const = default;
};
Result<Frame> encode_joint_fault_clear(std::uint8_t servo, const ServoRange& servos);
Result<JointFaultClearReply> decode_joint_fault_clear_reply(const Frame& frame);
Frame encode_joint_fault_clear_reply(const JointFaultClearReply& reply);

}  // namespace armctl::rc
