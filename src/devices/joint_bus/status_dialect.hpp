// What a STATUS word means. Two dialects exist on real buses (spec "Legacy dialect"):
// standard = 100 + 10 x command on success, 930/940 on error; legacy (the original joint
// firmware) = the command code itself on success, 93/94 on error.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace armctl::joint_bus {

enum class Dialect { standard, legacy };

const char* to_string(Dialect dialect);
std::optional<Dialect> dialect_from_string(std::string_view name);  // "standard" | "legacy"

enum class StatusMeaning { success, unknown_command, bad_data, unexpected };

// Interprets `status` as the answer to `command` in `dialect`. A success code that belongs
// to another command is `unexpected`: the joint answered something we did not ask. A
// command the joints do not know has no success code at all: whatever it is answered with
// is an error or unexpected (in the legacy dialect command 93 answered with 93 is
// unknown_command, not success).
StatusMeaning interpret_status(Dialect dialect, std::int16_t command, std::int16_t status);

// The STATUS a joint sends for success of `command` in `dialect`; empty for a command
// code no joint knows (there is no success for it).
std::optional<std::int16_t> success_status(Dialect dialect, std::int16_t command);

// Highest set_speed value the joints accept: 100 (%) standard, 255 (PWM cap) legacy.
int max_speed_value(Dialect dialect);

}  // namespace armctl::joint_bus
