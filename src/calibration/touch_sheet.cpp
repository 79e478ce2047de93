#include "calibration/touch_sheet.hpp"

#include <cmath>

#include <fmt/core.h>

#include "core/printable.hpp"

namespace armctl::calibration {

SheetPlacement default_placement(const arm::ArmModel& model) {
  if (model.family == "scara") return SheetPlacement{0.250, 0.050};
  return SheetPlacement{0.060, 0.0};
}

Result<std::vector<NamedPoint>> sheet_points(const arm::ArmModel& model, const SheetPlacement& placement) {
  if (!std::isfinite(placement.distance) || !std::isfinite(placement.height) || placement.distance < 0.020)
    return Error{ErrorKind::invalid_argument,
                 fmt::format("sheet placement: distance {:.1f} mm and height {:.1f} mm; the distance must be at least "
                             "20 mm (the sheet lies in front of the base), both finite",
                             placement.distance * 1e3, placement.height * 1e3)};
  std::vector<NamedPoint> out;
  for (const SheetMark& m : kSheetMarks) {
    // The sheet's x runs away from the arm; its left edge (u = 0) is on the arm's left (+y)
    // as the arm faces the sheet.
    const Eigen::Vector3d p(placement.distance + m.v, kSheetWidth / 2 - m.u, placement.height);
    if (Status s = arm::within_reach(model, p, fmt::format("sheet mark {}", m.name)); !s) return s.error();
    out.push_back(NamedPoint{m.name, p});
  }
  return out;
}

Result<NamedPoint> user_point(const arm::ArmModel& model, std::string name, const Eigen::Vector3d& position) {
  if (name.empty()) return Error{ErrorKind::invalid_argument, "a user point needs a name"};
  if (Status s = arm::within_reach(model, position, fmt::format("point '{}'", printable(name))); !s) return s.error();
  return NamedPoint{std::move(name), position};
}

}  // namespace armctl::calibration
