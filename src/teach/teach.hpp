// Teaching an arm by hand: torque off (xArm) or the position loops off (SCARA), the arm
// moved by hand, its position recorded as named points (files/points_file.hpp) or as a
// continuous recording (motion/recording.hpp); torque back on at the end holding the arm
// where it stands, whatever the way out. Docs: docs/teach.md.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "arm/arm.hpp"
#include "core/error.hpp"
#include "files/recording_file.hpp"
#include "files/points_file.hpp"

namespace armctl::teach {

// Torque off for as long as it lives; on destruction (normal end, error, exception)
// torque back on holding where the arm stands. release() does that early and says how it went.
class LimpArm {
 public:
  static Result<std::unique_ptr<LimpArm>> make(arm::Arm& arm);
  ~LimpArm();
  Status release();
  LimpArm(const LimpArm&) = delete;
  LimpArm& operator=(const LimpArm&) = delete;

 private:
  explicit LimpArm(arm::Arm& arm) : arm_(arm) {}
  arm::Arm& arm_;
  bool released_ = false;
};

// The point `name` at `positions` (SI, every joint): joint values, not a pose — a pose
// loses the configuration (elbow) and needs IK to come back, joints replay exactly.
files::Point point_at(const arm::ArmModel& model, const std::vector<double>& positions, std::string name);

// What teaching a point says, as a value: the CLI prints `text`, or under --json the fields.
enum class TeachEventKind { started, recorded, replaced, refused, finished };
struct TeachEvent {
  TeachEventKind kind;
  std::string text;               // one line for a person (every kind)
  std::string name;               // recorded, replaced: the point; refused: the name typed
  std::vector<double> positions;  // recorded, replaced: every joint, SI
  std::size_t points = 0;         // finished: how many recorded
};
const char* to_string(TeachEventKind kind);  // "started", "recorded", ...

struct TeachIo {
  // The next line typed; nullopt at the end (end of input, Ctrl-C).
  std::function<std::optional<std::string>()> next_line;
  std::function<void(const TeachEvent&)> on_event;
};

// Teaches points into `points_path` (read first if it exists, so points are added to it):
// torque off, then each line records where the arm stands under the name typed (spaces
// around it ignored), or p1, p2, ... (the first free) for an empty line; a name already in
// the file is replaced. The file is written after every point. A bad name is said and
// nothing recorded; teaching goes on. The file is written keeping its comments and every
// other line (files::write_points_file). A file that does not parse or cannot be written
// (read-only, no such directory) is refused before torque goes off. Returns the number of
// points recorded.
Result<std::size_t> teach_points(arm::Arm& arm, const std::filesystem::path& points_path, const TeachIo& io);

struct RecordOptions {
  double rate = 20;  // Hz
  std::optional<Duration> duration;  // stop after this long (device time)
  // Asked before every sample: true ends the recording (Enter, end of input, Ctrl-C).
  std::function<bool()> done;
  std::function<void(const motion::RecordingSample&)> on_sample;
  // Called once torque is off, just before the first sample (the CLI says "move the arm").
  std::function<void()> on_start;
};

// Records the arm's joints at `rate` on the device's clock (torque off for the time) until
// done() or the duration. At least one sample. A rate faster than one read of every joint
// allows is refused before torque goes off, naming the rate the link allows.
Result<motion::Recording> record_motion(arm::Arm& arm, const RecordOptions& options);

}  // namespace armctl::teach
