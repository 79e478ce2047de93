// Recordings: a continuous motion taken by `armctl teach --record` (joint positions at a
// fixed rate) and played back by `armctl replay` (format reference: docs/teach.md).
//
//   # armctl recording
//   arm xarm
//   rate 20Hz
//   joints base:deg shoulder:deg elbow:deg wrist_pitch:deg wrist_roll:deg gripper:mm
//   0.000  0.000 30.000 -45.000 -60.000 0.000 10.000
//   0.050  0.250 30.125 -45.000 -60.000 0.000 10.000
//
// Header lines in this order: the arm's name, the rate (1..1000 Hz), the joints (their
// names and the unit the values are written in: deg or rad for angles, mm or m for lengths).
// Then one sample per line: the time in s since the start (from 0, increasing), then one
// value per joint. '#' starts a comment; blank lines are ignored. 1..kRecordingMaxSamples
// samples. Errors name the file, line and column, what was found and what is expected;
// nothing is returned on error. The values (Recording) and replay's steps on them:
// motion/recording.hpp.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "motion/recording.hpp"

namespace armctl::files {

inline constexpr std::size_t kRecordingMaxSamples = 200'000;  // 2.7 h at 20 Hz
inline constexpr std::size_t kRecordingMaxJoints = 16;
inline constexpr double kRecordingMaxRate = 1000;  // Hz

Result<motion::Recording> parse_recording(std::string_view text, std::string_view source = "<recording>");
// Reads a regular file of at most 64 MiB, then parses it.
Result<motion::Recording> read_recording(const std::filesystem::path& path);
// Values in deg and mm with enough digits that parse_recording(format_recording(r))
// gives r back to within 1e-9 (of a degree or mm).
std::string format_recording(const motion::Recording& recording);
// Writes atomically (a temporary file renamed over `path`).
Status write_recording(const std::filesystem::path& path, const motion::Recording& recording);

// "20Hz", "20 Hz", "20": a recording rate in 1..1000 Hz; errors (invalid_argument) say
// what is allowed.
Result<double> parse_rate(std::string_view text);

}  // namespace armctl::files
