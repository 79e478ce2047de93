// How a simulated arm is mis-assembled on purpose (`sim?miscal=SEED`, `armctl sim ... --miscal
// SEED`): zeros shifted, one direction flipped, link lengths off by a few millimetres and, on
// the xArm, one servo answering another's ID. Chosen from the seed, deterministically on every
// platform (own generator, no std:: distributions), so a test and the simulator it drives agree
// on the truth. The simulators (devices/joint_sim, devices/xarm_emulator) apply it; a test or
// the calibration wizard's tests read it back to check what the wizard recovered.
//
// Device positions are the device's own units, per device ID (the xArm's servo ID, the
// SCARA's joint number, 1-based):
//   true   what a well-built arm (the one the shipped arm file describes) would read at the
//          pose the physical arm stands in
//   device what the mis-assembled arm reads there
//   true = pivot + (flipped ? -1 : 1) * (device - pivot) + zero_shift
// pivot: 500 on the xArm (a servo mounted reversed mirrors about its centre), 0 on the SCARA
// (where the encoder counted from when the joint was homed or powered on). Ranges:
// docs/simulator.md "Mis-assembled simulators".
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"

namespace armctl {

enum class MiscalArm { scara, xarm };
const char* to_string(MiscalArm arm);

struct JointMiscal {
  double zero_shift = 0;  // device units, whole: true - device at the pivot
  bool flipped = false;   // the joint turns the other way than the arm file says
};

// A link whose length is off: the origin of URDF joint `joint` is `error_mm` longer along its
// own direction (negative: shorter). The true geometry is the URDF with these applied.
struct LinkError {
  std::string joint;
  double error_mm = 0;
};

// On the xArm: the servo mounted where servo `place` belongs answers ID `answers_as` (another
// servo's), so two servos answer `answers_as` and none answers `place`.
struct DuplicateId {
  int place = 0;
  int answers_as = 0;
};

struct Miscalibration {
  MiscalArm arm = MiscalArm::xarm;
  std::uint32_t seed = 0;
  double pivot = 0;
  std::vector<JointMiscal> joints;  // index = device ID - 1
  std::vector<LinkError> links;
  std::optional<DuplicateId> duplicate;

  // Device ID 1..joints.size(); throws invalid_argument for any other.
  const JointMiscal& joint(int id) const;
  // The true position at a device position, and back.
  double true_position(int id, double device) const;
  double device_position(int id, double true_position) const;
  // The device position at which this joint stands where a well-built one stands at `true`
  // device position (e.g. the arm file's zero): what calibrating the zero must find.
  double device_zero(int id, double true_zero) const { return device_position(id, true_zero); }
  // The URDF joint's length error in mm (0 if the link is not off).
  double link_error_mm(std::string_view urdf_joint) const;
};

// The mis-assembly of `seed` for that arm. Ranges (docs/simulator.md):
//   zero shifts   xArm servos 8..60 units (2..14 deg), and for odd seeds one chain servo
//                 130..170 units, beyond a servo's own offset range (-125..125); SCARA revolute
//                 joints 56..420 clicks (2..15 deg), Z 200..1500 clicks (2..15 mm), gripper
//                 none (its open/closed positions are calibrated apart)
//   direction     exactly one chain joint flipped (xArm servos 2..6; SCARA joints 2..6)
//   lengths       +-1..5 mm each: xArm servo5, servo4, servo3, servo2 origins (shoulder height,
//                 upper arm, forearm, wrist); SCARA UAE, UAJ origins (upper arm, forearm)
//   duplicate ID  xArm only: one chain servo (2..6) answers another chain servo's ID
Miscalibration make_miscalibration(MiscalArm arm, std::uint32_t seed);
// A well-built arm (every shift 0, nothing flipped, no length error, no duplicate): the truth
// of a simulator without miscal, for the same checks.
Miscalibration no_miscalibration(MiscalArm arm);

// Every value, one line, for the simulators' debug log (never their normal output):
// "miscal 7 (xarm): servo 1 zero +12, servo 2 zero -40 flipped, ... ; link servo4 +3.2 mm, ...;
// servo 5 answers ID 3".
std::string describe(const Miscalibration& m);

// The seed of `miscal=TEXT` (a URI key or a command-line option, named `key` in errors), or
// invalid_argument naming the key, the value and what is allowed (a whole number
// 0..4294967295).
Result<std::uint32_t> parse_miscal_seed(std::string_view key, std::string_view text);

}  // namespace armctl
