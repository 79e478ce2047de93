// Robot Commands command codes (the CMD byte), as in spec/robot-commands.md.
#pragma once

#include <cstdint>
#include <optional>

namespace armctl::rc {

enum class Command : std::uint8_t {
  MultiServoMove = 3,
  GroupDownload = 5,
  GroupRun = 6,
  GroupStop = 7,
  GroupErase = 8,
  GroupSpeed = 11,
  GetBatteryVoltage = 15,
  MultiServoOff = 20,
  ServoPositionRead = 21,
  ServoOffsetWrite = 22,
  ServoOffsetRead = 23,
  ServoOffsetAdjust = 24,
  ServoSpeed = 26,
  BusServoInfoWrite = 27,
  BusServoInfoRead = 28,
};

// The command for a CMD byte, or nothing if the byte is not a Robot Commands code.
std::optional<Command> command_from_byte(std::uint8_t cmd);

// "MultiServoMove" etc.; "unknown" for values outside the enum.
const char* command_name(Command cmd);

// Notifications reuse the codes of the group commands (spec "Action groups").
constexpr std::uint8_t kNotifyGroupStarted = 6;
constexpr std::uint8_t kNotifyGroupStopped = 7;
constexpr std::uint8_t kNotifyGroupFinished = 8;

}  // namespace armctl::rc
