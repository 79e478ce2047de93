// `armctl arm calibrate zero`: where the joints stand becomes their zero. The arm file's
// device mapping of each joint moves by the joint's current value, and its position limits
// move with it (the joint's travel stays where it was on the device), kept inside the
// URDF's limits (the URDF's zero pose is, from now on, where the arm stands). Refused before
// anything is written: a joint that stands outside its limits, and a limit that would fall
// outside the device's range (such a limit is pulled in to the device's end for a single
// joint; for a coupled pair, whose ends mix two actuators, the zero is refused). Written to
// the arm file in one atomic replacement.
#pragma once

#include <optional>
#include <vector>

#include "arm/arm_model.hpp"
#include "core/error.hpp"

namespace armctl::arm {

struct ZeroChange {
  int joint = 0;       // index in the model
  double shift = 0;    // the joint's value before (SI): what it reads as 0 from now on
  DeviceMap map;       // the new mapping
  JointLimits limits;  // the new limits (the old ones, shifted, within the device's range)
};

// `device_now`: every joint's device position, as read. `joints`: the indices to zero; the
// two joints of a coupling must be zeroed together.
Result<std::vector<ZeroChange>> calibrate_zero(const ArmModel& model, Protocol protocol,
                                               const std::vector<double>& device_now,
                                               const std::vector<int>& joints);

// A coupled pair's actuators carry mixes of both joints, so its limits hold on the device only
// if every corner of the two ranges does: the first actuator driven beyond `protocol`'s
// device range (by more than `slack` device units) at a corner of `model`'s limits, and the
// device position it would need; nothing when every corner fits.
struct CoupledOverrun {
  int actuator = 0;    // joint index whose device position is out of range
  double device = 0;   // the device position that corner needs
};
std::optional<CoupledOverrun> coupled_overrun(const ArmModel& model, Protocol protocol, const Coupling& pair,
                                              double slack = 0);

}  // namespace armctl::arm
