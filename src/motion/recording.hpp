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
// nothing is returned on error.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "core/quantity.hpp"

namespace armctl::motion {

inline constexpr std::size_t kRecordingMaxSamples = 200'000;  // 2.7 h at 20 Hz
inline constexpr std::size_t kRecordingMaxJoints = 16;
inline constexpr double kRecordingMaxRate = 1000;  // Hz

struct RecordingJoint {
  std::string name;
  Dimension dimension = Dimension::angle;
  bool operator==(const RecordingJoint&) const = default;
};

struct RecordingSample {
  double time = 0;                // s since the first sample's start
  std::vector<double> positions;  // SI, one per joint
  bool operator==(const RecordingSample&) const = default;
};

struct Recording {
  std::string arm;  // the arm model's name ("xarm", "scara")
  double rate = 20;  // Hz, as asked when recording
  std::vector<RecordingJoint> joints;
  std::vector<RecordingSample> samples;
  bool operator==(const Recording&) const = default;
};

Result<Recording> parse_recording(std::string_view text, std::string_view source = "<recording>");
// Reads a regular file of at most 64 MiB, then parses it.
Result<Recording> read_recording(const std::filesystem::path& path);
// Values in deg and mm with enough digits that parse_recording(format_recording(r))
// gives r back to within 1e-9 (of a degree or mm).
std::string format_recording(const Recording& recording);
// Writes atomically (a temporary file renamed over `path`).
Status write_recording(const std::filesystem::path& path, const Recording& recording);

// "20Hz", "20 Hz", "20": a recording rate in 1..1000 Hz; errors (invalid_argument) say
// what is allowed.
Result<double> parse_rate(std::string_view text);

// Replay support, pure. Each position the mean of the samples within `half_window` either
// side (fewer at the ends; the first and last samples kept as they are): takes out the
// hand's tremor and the position reads' quantization.
std::vector<RecordingSample> smooth(const std::vector<RecordingSample>& samples, std::size_t half_window);
// The indices of the samples to keep as waypoints so that the straight line (in joint space,
// over time) between kept samples stays within `tolerance[j]` of every dropped sample, for
// every joint j (Douglas-Peucker). Always keeps the first and the last.
std::vector<std::size_t> keep_samples(const std::vector<RecordingSample>& samples,
                                      const std::vector<double>& tolerance);

}  // namespace armctl::motion
