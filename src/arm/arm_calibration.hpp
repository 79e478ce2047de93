// `armctl arm calibrate zero`: where the joints stand becomes their zero. The arm file's
// device mapping of each joint moves by the joint's current value; the change is checked
// (the joint's limits must still fit the device's range, and zero must lie inside them)
// before anything is written, and written to the arm file in one atomic replacement.
#pragma once

#include <vector>

#include "arm/arm_model.hpp"
#include "core/error.hpp"

namespace armctl::arm {

struct ZeroChange {
  int joint = 0;       // index in the model
  double shift = 0;    // the joint's value before (SI): what it reads as 0 from now on
  DeviceMap map;       // the new mapping
};

// `device_now`: every joint's device position, as read. `joints`: the indices to zero; the
// two joints of a coupling must be zeroed together.
Result<std::vector<ZeroChange>> calibrate_zero(const ArmModel& model, Protocol protocol,
                                               const std::vector<double>& device_now,
                                               const std::vector<int>& joints);

// Rewrites model.file with the new mappings (other content kept; formatting is the JSON
// library's). Nothing is written if any change cannot be applied.
Status save_calibration(const ArmModel& model, Protocol protocol, const std::vector<ZeroChange>& changes);

}  // namespace armctl::arm
