// Recordings: a continuous motion taken by `armctl teach --record` (joint positions at a
// fixed rate) and played back by `armctl replay`, as values, and the pure steps of a
// replay (smoothing, choosing waypoints). The file format: files/recording_file.hpp.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/quantity.hpp"

namespace armctl::motion {

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
