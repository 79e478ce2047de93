// The calibration wizard's engine (docs/calibration.md "The wizard"): one object over an arm
// that runs each step on the device, takes the user's answers and holds what they change as
// pending CalibrationChanges. Nothing is written until confirm(): then the servo offsets (on
// the xArm) and the arm file, once, through write_calibration. Destroyed without confirm(), or
// left by an exception, it changes nothing: the arm file is untouched and no servo offset was
// sent. Every app (the CLI `armctl calibrate`, later the dashboard and Python) is a thin
// adapter that prompts, shows and calls these functions; each step may be run alone, again
// (the new answer replaces the old one) or not at all.
//
// Readings: `read_joint` gives a joint's value as the arm file reads it NOW (before the
// pending changes); the steps take those and turn them into the new readings themselves,
// whatever order the steps were run in (a direction answered after the zero still gives the
// right zero).
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "arm/arm.hpp"
#include "calibration/calibration_changes.hpp"
#include "calibration/joint_steps.hpp"
#include "calibration/kinematic_fit.hpp"
#include "calibration/servo_bus.hpp"
#include "calibration/touch_sheet.hpp"
#include "calibration/touched_points.hpp"
#include "core/error.hpp"

namespace armctl::calibration {

struct SessionOptions {
  // Zero step on a servo bus: write the servo's own offset when it fits -125..125 (the
  // issue's rule); false: always the arm file's zero.
  bool servo_offsets = true;
  double wiggle_angle = 0.087;    // rad (5 deg): "which joint is which"
  double wiggle_length = 0.005;   // m
  double nudge_angle = 0.087;     // rad: "did it go the positive way"
  double nudge_length = 0.005;    // m
};

// Step 1: what answers.
struct DeviceAnswer {
  int id = 0;            // servo ID or joint number
  std::string joint;     // the joint the arm file gives that ID
  bool answers = false;  // a usable answer came
  std::optional<double> position;
};
struct FindReport {
  std::vector<DeviceAnswer> devices;
  // IDs the arm file has that gave no usable answer: on a servo bus two servos on one ID
  // (their replies collide) or none.
  std::vector<int> silent;
  std::string text;  // for people, one line per device and what to do
};

// Step 4's result, for the adapter to show.
struct ZeroResult {
  ZeroStep::Kind kind = ZeroStep::Kind::file_zero;
  double shift = 0;     // file zero: the joint's new zero, in its old readings (SI)
  int servo_offset = 0; // servo offset: units written at confirm
  std::string text;
};

class CalibrationSession {
 public:
  // `servos`: the xArm's servo bus (rc_servo_bus.hpp), or nullptr (a joint bus, or a device
  // the app cannot reach underneath); both must outlive the session.
  explicit CalibrationSession(arm::Arm& arm, ServoBus* servos = nullptr, SessionOptions options = {});

  const arm::ArmModel& model() const { return arm_.model(); }
  // A joint by its name or 1-based number as the wizard prints it ("servo3", "3"); the
  // error names what is allowed.
  Result<int> joint_named(const std::string& text) const;

  // ---- 1. find what answers
  Result<FindReport> find();
  // Gives the one servo connected the ID `id` (BusServoInfoWrite reaches EVERY servo on the
  // bus: the user unplugs the others first); then checks it answers alone.
  Status set_servo_id(int id);

  // ---- 2. which joint is which: moves `joint` a few degrees and back; `at_far_end` (if
  // given) is called while it stands out there (the dashboard highlights it then).
  Status wiggle(int joint, const std::function<void()>& at_far_end = {});
  // The user says which joint moved: Ok when it is `joint`, else an error naming both (the
  // servo with that joint's ID sits where `moved` belongs: give it the right ID, step 1).
  Status answer_which(int joint, int moved);

  // ---- 3. direction: moves `joint` a little in its positive direction (and leaves it there).
  Status nudge(int joint);
  Status answer_direction(int joint, bool went_as_shown);

  // ---- 4. zero: torque off; the user puts the joint at its mark by hand.
  Status release();
  // Torque on where the arm stands.
  Status hold();
  Result<double> read_joint(int joint);
  // The joint stands at its mark (`mark`: its true value there, 0 when the mark is the zero).
  Result<ZeroResult> zero_here(int joint, double mark = 0);

  // ---- 5. limits from the two ends (readings from read_joint, either order).
  Result<PositionRange> limits(int joint, double end_a, double end_b);
  // ---- 6. gripper: readings open and closed.
  Result<GripperPositions> gripper(double open, double closed);

  // ---- 7. touch points: the tool stands on `point`; the joints are read now.
  Result<TouchedPoint> touch(const NamedPoint& point);
  const std::vector<TouchedPoint>& touched() const { return touched_; }
  void clear_touched() { touched_.clear(); }
  // The touched points' residuals on the arm as the pending changes have it.
  Result<ResidualReport> verify() const;
  // ---- 8. the optional fit of zeros and link lengths from the touched points (10..30).
  Result<FitResult> fit();

  // Forget one joint's pending answers, or all.
  void forget(int joint);
  void forget_all();

  // What confirm() would write, checked as a whole (check_changes).
  Result<CalibrationChanges> changes() const;
  // For people: every pending change, one line each.
  std::string describe() const;
  // Writes: the servo offsets (adjust, save, read back), then the arm file (write_calibration,
  // `.prev` kept). A servo offset that does not read back stops it before the file; a file
  // that cannot be written puts the offsets back. Returns the model of the new file, which
  // the arm then drives with (Arm::use_model): pending answers and touched points are cleared,
  // and the session may go on calibrating from the new file.
  Result<arm::ArmModel> confirm();

 private:
  struct JointAnswers {
    std::optional<bool> flip;
    std::optional<double> zero_shift;      // in the old readings: new = sign * old + shift
    std::optional<int> servo_offset;       // units, with the servo's ID below
    int servo = 0;
    int held_offset = 0;                   // the offset the servo held at the zero step
    double offset_shift = 0;               // the same zero in old readings (for verify/fit)
    std::optional<std::pair<double, double>> ends;  // old readings
    double fit_correction = 0;             // added to the new reading
  };
  double sign(int joint) const;
  double shift(int joint, bool for_readings) const;
  double new_reading(int joint, double old) const { return sign(joint) * old + shift(joint, true); }
  std::vector<TouchedPoint> new_readings(const std::vector<TouchedPoint>& points) const;
  Status check_joint(int joint) const;
  void cut_to_devices(int joint, double zero_shift, PositionRange& range) const;
  Status move_by(int joint, double amount);

  arm::Arm& arm_;
  ServoBus* servos_;
  SessionOptions options_;
  std::map<int, JointAnswers> joints_;
  std::optional<std::pair<double, double>> gripper_;  // old readings: open, closed
  std::vector<motion::OriginLength> link_lengths_;
  std::vector<TouchedPoint> touched_;
};

}  // namespace armctl::calibration
