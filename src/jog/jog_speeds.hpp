// The speed steps every jog input shares (keys, gamepad): the tool's linear (mm/s) and
// angular (deg/s) speed, a joint's fraction of its velocity limit. Slow first steps for
// placing a tool by eye, fast last ones for crossing the workspace.
#pragma once

#include <array>

namespace armctl::jog {

inline constexpr std::array<double, 5> kLinearSteps{5, 10, 25, 50, 100};
inline constexpr std::array<double, 5> kAngularSteps{5, 10, 20, 40, 60};
inline constexpr std::array<double, 5> kJointFractionSteps{0.05, 0.1, 0.25, 0.5, 1.0};
inline constexpr int kSpeedSteps = int(kLinearSteps.size());
inline constexpr int kStartSpeedStep = 2;

}  // namespace armctl::jog
