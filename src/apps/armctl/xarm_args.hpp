// Argument parsing for `armctl xarm`: servo=position entries, group numbers, servo lists.
// Every error names the argument and what is allowed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "devices/robot_commands/client.hpp"

namespace armctl::cli::xarm_args {

// "1=500", "2=30deg", "3=-12.5deg", "4=keep" (leave alone) for servos 1..servo_count.
robot_commands::ServoTarget parse_target(const std::string& text, int servo_count);
// "1", "6" within 1..servo_count.
std::uint8_t parse_servo(const std::string& text, int servo_count);
// Servo list; empty = every servo.
std::vector<std::uint8_t> parse_servos(const std::vector<std::string>& texts, int servo_count);
// 0..254, or "all"/255 when all_allowed.
std::uint8_t parse_group(const std::string& text, bool all_allowed);
// Whole number within [min, max], `what` names it in errors.
long parse_int(const std::string& text, long min, long max, const std::string& what);

}  // namespace armctl::cli::xarm_args
