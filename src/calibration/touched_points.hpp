// Touched points and their residuals: the arm's tool point put on a point whose position is
// known (a mark of the printed sheet, a point the user measured), with the joints' readings
// there. What the verify step reports and the kinematic fit minimises (docs/calibration.md).
#pragma once

#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "arm/arm_model.hpp"
#include "core/error.hpp"

namespace armctl::calibration {

struct TouchedPoint {
  std::string name;             // "A1", "corner", ... for the report
  std::vector<double> joints;   // every chain joint's reading there (SI, the model's order)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // where the point is (base frame, m)
};

struct PointResidual {
  std::string name;
  Eigen::Vector3d error = Eigen::Vector3d::Zero();  // where the model puts the tool minus the point (m)
  double distance = 0;                              // |error| (m)
};

struct ResidualReport {
  std::vector<PointResidual> points;
  double rms = 0, max = 0;  // of the distances (m)
  std::string worst;        // the point with the largest one
};

// Ok, or invalid_argument naming the point: one reading per chain joint, finite, inside the
// joint's limits (with a rounding slack), and a finite position within the arm's reach.
Status check_touched_points(const arm::ArmModel& model, std::span<const TouchedPoint> points);

// The report from the errors, in the points' order.
ResidualReport residual_report(std::vector<PointResidual> points);

// Verify: where the arm's model (its kinematics and tool frame, as loaded) puts the tool at
// each point's readings, against where the point is.
Result<ResidualReport> verify_points(const arm::ArmModel& model, std::span<const TouchedPoint> points);

// "A1 0.42 mm, A2 1.10 mm, ...; rms 0.80 mm, max 1.10 mm (A2)": for logs and test messages.
std::string to_text(const ResidualReport& report);

}  // namespace armctl::calibration
