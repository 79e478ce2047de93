// The kinematic fit (docs/calibration.md "The fit"): from 10..30 touched points, the joints'
// zeros and the link lengths that put the model's tool point nearest the known points, in
// the least-squares sense (Levenberg-Marquardt, numeric Jacobian). Refused, before any
// iteration, when the points cannot tell a parameter apart from the others (the
// identifiability rule), naming it; the refusal carries an Unidentifiable detail.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "arm/arm_model.hpp"
#include "calibration/calibration_chain.hpp"
#include "calibration/calibration_changes.hpp"
#include "calibration/touched_points.hpp"
#include "core/error.hpp"

namespace armctl::calibration {

// A fit needs at least this many points (3 equations each) to say anything of its residuals.
inline constexpr std::size_t kMinFitPoints = 10;
// The smallest singular value of the column-scaled Jacobian, over its largest, that a fit
// accepts: below it, some combination of parameters moves the tool point less than
// 1/1000 of what each does alone, and noise decides its value.
inline constexpr double kMinCondition = 1e-3;

// Which parameters the fit adjusts on an arm, and those it leaves out with why: every joint's
// zero and every origin length, less those whose effect on the tool point, over poses spread
// across the joints' limits, is a combination of the others' (the same rule as the fit's
// refusal, on generic poses: such a parameter can be told apart by no set of points).
struct ParameterChoice {
  std::vector<Parameter> fitted;
  struct LeftOut {
    Parameter parameter;
    std::vector<Parameter> same_as;  // the fitted parameters it cannot be told apart from
    std::string why;                 // for people
  };
  std::vector<LeftOut> left_out;
};
Result<ParameterChoice> fittable_parameters(const arm::ArmModel& model);

// The refusal's detail: the parameter the points cannot tell apart, and from which others.
struct Unidentifiable {
  Parameter parameter;
  std::vector<Parameter> same_as;  // empty: it has no effect on the points at all
  double condition = 0;            // as kMinCondition measures it
};

struct ParameterEstimate {
  Parameter parameter;
  double correction = 0;   // added to the reading (zero, rad or m) or to the length (m)
  double uncertainty = 0;  // one standard deviation, from the residuals left (same unit)
  double length = 0;       // a length's value after the fit (m); 0 for a zero
};

struct FitResult {
  std::vector<ParameterEstimate> estimates;
  ResidualReport before, after;
  double condition = 0;
  int iterations = 0;
  // The parameters fitted, in the order of `estimates`.
  std::vector<Parameter> parameters() const;
};

struct FitOptions {
  std::vector<Parameter> parameters;  // empty: fittable_parameters(model).fitted
  double min_condition = kMinCondition;
  int max_iterations = 100;
};

Result<FitResult> fit_kinematics(const arm::ArmModel& model, std::span<const TouchedPoint> points,
                                 const FitOptions& options = {});

// Verify before anything is written: the residuals of `points` (others than the fit's,
// e.g. the sheet's marks) on the arm as the fit has it. Readings as for the fit.
Result<ResidualReport> verify_fit(const arm::ArmModel& model, const FitResult& fit,
                                  std::span<const TouchedPoint> points);

// The fit as arm-file changes: each fitted zero a zero shift of its joint (limits carried
// over), each fitted length the origin's new length. Written with write_calibration.
CalibrationChanges changes_from_fit(const arm::ArmModel& model, const FitResult& fit);

}  // namespace armctl::calibration
