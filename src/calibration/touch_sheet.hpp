// The verify sheet (docs/calibration.md "The sheet", docs/images/calibration-sheet.svg): an A4
// page, portrait, with five marks at known places, laid in front of the arm with its near
// edge square to the base's x axis and centred on it. Where each mark is in the base frame
// follows from where the sheet lies (SheetPlacement). User points (measured with a ruler)
// join the same list by name.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "arm/arm_model.hpp"
#include "core/error.hpp"

namespace armctl::calibration {

// A4 portrait: across (u) and away from the arm (v), in m.
inline constexpr double kSheetWidth = 0.210, kSheetLength = 0.297;

// A mark on the sheet: u across from the sheet's left edge, v from its near edge (m), as the
// sheet's picture draws it.
struct SheetMark {
  const char* name;
  double u, v;
};
// A, B near the arm; C in the middle; D, E far from it.
inline constexpr SheetMark kSheetMarks[] = {
    {"A", 0.045, 0.030}, {"B", 0.165, 0.030}, {"C", 0.105, 0.100}, {"D", 0.045, 0.170}, {"E", 0.165, 0.170}};

struct SheetPlacement {
  double distance = 0;  // from the base's z axis to the sheet's near edge, along x (m)
  double height = 0;    // of the sheet's surface above the base frame's origin (m)
};
// Where the sheet goes on each shipped arm: the xArm's on the table its base stands on,
// 60 mm from the base axis; the SCARA's on a block, its surface 50 mm above the base frame
// (the tool reaches no lower than 25 mm), 250 mm from the column.
SheetPlacement default_placement(const arm::ArmModel& model);

struct NamedPoint {
  std::string name;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // base frame, m
};

// The marks' positions in the base frame. Refused: a placement that is not finite, with
// the sheet's near edge closer than 20 mm to the base axis, or a mark beyond the arm's reach.
Result<std::vector<NamedPoint>> sheet_points(const arm::ArmModel& model, const SheetPlacement& placement);

// A point the user names, checked: a name, finite, within the arm's reach.
Result<NamedPoint> user_point(const arm::ArmModel& model, std::string name, const Eigen::Vector3d& position);

}  // namespace armctl::calibration
