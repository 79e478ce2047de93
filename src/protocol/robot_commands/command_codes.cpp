#include "protocol/robot_commands/command_codes.hpp"

namespace armctl::rc {

std::optional<Command> command_from_byte(std::uint8_t cmd) {
  switch (static_cast<Command>(cmd)) {
    case Command::MultiServoMove:
    case Command::GroupDownload:
    case Command::GroupRun:
    case Command::GroupStop:
    case Command::GroupErase:
    case Command::GroupSpeed:
    case Command::GetBatteryVoltage:
    case Command::MultiServoOff:
    case Command::ServoPositionRead:
    case Command::ServoOffsetWrite:
    case Command::ServoOffsetRead:
    case Command::ServoOffsetAdjust:
    case Command::ServoSpeed:
    case Command::BusServoInfoWrite:
    case Command::BusServoInfoRead:
      return static_cast<Command>(cmd);
  }
  return std::nullopt;
}

const char* command_name(Command cmd) {
  switch (cmd) {
    case Command::MultiServoMove: return "MultiServoMove";
    case Command::GroupDownload: return "GroupDownload";
    case Command::GroupRun: return "GroupRun";
    case Command::GroupStop: return "GroupStop";
    case Command::GroupErase: return "GroupErase";
    case Command::GroupSpeed: return "GroupSpeed";
    case Command::GetBatteryVoltage: return "GetBatteryVoltage";
    case Command::MultiServoOff: return "MultiServoOff";
    case Command::ServoPositionRead: return "ServoPositionRead";
    case Command::ServoOffsetWrite: return "ServoOffsetWrite";
    case Command::ServoOffsetRead: return "ServoOffsetRead";
    case Command::ServoOffsetAdjust: return "ServoOffsetAdjust";
    case Command::ServoSpeed: return "ServoSpeed";
    case Command::BusServoInfoWrite: return "BusServoInfoWrite";
    case Command::BusServoInfoRead: return "BusServoInfoRead";
  }
  return "unknown";
}

}  // namespace armctl::rc
