#include "calibration/kinematic_fit.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <fmt/core.h>

namespace armctl::calibration {

namespace {

// Row-major on purpose: libompl.so (the --avoid planner) instantiates Eigen's JacobiSVD and
// ColPivHouseholderQR of MatrixXd too, and in the sanitizer build an executable that defines
// the same instantiations exports them, so OMPL's calls land in ours. Eigen's allocator
// differs under ASan (its own aligned malloc, not malloc's), and OMPL then frees what ours
// allocated (a bad free in `move-to --avoid`). Another storage order is another
// instantiation: each side keeps its own.
using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using Vector = Eigen::VectorXd;

// Central differences: rad and m both, a step well above rounding and well below any
// curvature of the chain over it.
constexpr double kStep = 1e-6;

Vector readings(const TouchedPoint& p) { return Eigen::Map<const Vector>(p.joints.data(), Eigen::Index(p.joints.size())); }

// Stacked model-minus-point errors, 3 per point.
Vector residual(const CalibrationChain& chain, std::span<const TouchedPoint> points, const std::vector<Parameter>& ps,
                const Vector& x) {
  Vector r(3 * Eigen::Index(points.size()));
  for (std::size_t k = 0; k < points.size(); ++k)
    r.segment<3>(3 * Eigen::Index(k)) = chain.tool_point(readings(points[k]), ps, x) - points[k].position;
  return r;
}

// Tool points at joint readings `qs` (no known points): the Jacobian of the tool points
// with respect to the parameters, at corrections x.
Matrix jacobian(const CalibrationChain& chain, const std::vector<Vector>& qs, const std::vector<Parameter>& ps,
                const Vector& x) {
  Matrix j(3 * Eigen::Index(qs.size()), Eigen::Index(ps.size()));
  for (Eigen::Index c = 0; c < j.cols(); ++c) {
    Vector hi = x, lo = x;
    hi[c] += kStep;
    lo[c] -= kStep;
    for (std::size_t k = 0; k < qs.size(); ++k)
      j.block<3, 1>(3 * Eigen::Index(k), c) =
          (chain.tool_point(qs[k], ps, hi) - chain.tool_point(qs[k], ps, lo)) / (2 * kStep);
  }
  return j;
}

std::string names(const std::vector<Parameter>& ps) {
  std::string out;
  for (std::size_t i = 0; i < ps.size(); ++i)
    out += (i == 0 ? "" : i + 1 == ps.size() ? " and " : ", ") + ps[i].name;
  return out;
}

// The parameters whose columns, in the least-squares combination of `kept` that best makes
// `column`, weigh at least a tenth of the heaviest.
std::vector<Parameter> combination_of(const Matrix& kept_columns, const std::vector<Parameter>& kept,
                                      const Vector& column) {
  const Vector a = kept_columns.colPivHouseholderQr().solve(column);
  std::vector<Parameter> out;
  if (a.size() == 0) return out;
  const double heaviest = a.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < a.size(); ++i)
    if (std::abs(a[i]) >= 0.1 * heaviest) out.push_back(kept[std::size_t(i)]);
  return out;
}

// A zero moves the tool by about its lever times the angle; a length by itself. Columns
// are scaled to unit norm so that neither unit decides the conditioning (Jacobi scaling).
Vector column_norms(const Matrix& j) {
  Vector n(j.cols());
  for (Eigen::Index c = 0; c < j.cols(); ++c) n[c] = j.col(c).norm();
  return n;
}

}  // namespace

std::vector<Parameter> FitResult::parameters() const {
  std::vector<Parameter> out;
  for (const ParameterEstimate& e : estimates) out.push_back(e.parameter);
  return out;
}

Result<ParameterChoice> fittable_parameters(const arm::ArmModel& model) {
  auto chain = CalibrationChain::make(model);
  if (!chain) return chain.error();
  // Poses spread over the joints' limits (a fixed seed: the same choice every run).
  std::mt19937 random(25);
  std::vector<Vector> qs;
  for (int k = 0; k < 60; ++k) {
    Vector q(chain->joint_count());
    for (int i = 0; i < q.size(); ++i) {
      const arm::JointLimits& l = model.joints[std::size_t(i)].limits;
      q[i] = std::uniform_real_distribution<double>(l.lower, l.upper)(random);
    }
    qs.push_back(q);
  }
  const std::vector<Parameter>& all = chain->candidates();
  const Matrix j = jacobian(*chain, qs, all, Vector::Zero(Eigen::Index(all.size())));
  // In the order of preference, each parameter kept when its column adds a direction the
  // kept ones do not span (Gram-Schmidt on unit columns; structural dependencies leave
  // ~1e-10, a parameter of its own ~1).
  ParameterChoice choice;
  // A column this much smaller than the largest is rounding of the differences: no effect.
  const double largest = column_norms(j).maxCoeff();
  Matrix basis(j.rows(), 0), kept_columns(j.rows(), 0);
  for (std::size_t c = 0; c < all.size(); ++c) {
    const double norm = j.col(Eigen::Index(c)).norm();
    const bool no_effect = !(norm > 1e-9 * largest);
    Vector unit = no_effect ? Vector::Zero(j.rows()) : Vector(j.col(Eigen::Index(c)) / norm);
    Vector rest = unit;
    if (basis.cols() > 0) rest -= basis * (basis.transpose() * unit);
    if (no_effect || rest.norm() < 1e-6) {
      ParameterChoice::LeftOut out{all[c], {}, ""};
      if (no_effect || kept_columns.cols() == 0) {
        out.why = fmt::format("{} does not move the tool point (the tool point lies on the joint's axis)", all[c].name);
      } else {
        out.same_as = combination_of(kept_columns, choice.fitted, unit);
        out.why = fmt::format("{} moves the tool point as {} do{}, at every pose: no set of points tells it apart",
                              all[c].name, names(out.same_as), out.same_as.size() == 1 ? "es" : "");
      }
      choice.left_out.push_back(std::move(out));
      continue;
    }
    basis.conservativeResize(Eigen::NoChange, basis.cols() + 1);
    basis.col(basis.cols() - 1) = rest / rest.norm();
    kept_columns.conservativeResize(Eigen::NoChange, kept_columns.cols() + 1);
    kept_columns.col(kept_columns.cols() - 1) = unit;
    choice.fitted.push_back(all[c]);
  }
  return choice;
}

Result<FitResult> fit_kinematics(const arm::ArmModel& model, std::span<const TouchedPoint> points,
                                 const FitOptions& options) {
  auto made = CalibrationChain::make(model);
  if (!made) return made.error();
  const CalibrationChain& chain = *made;
  if (points.empty())
    return Error{ErrorKind::invalid_argument, fmt::format("no touched points to fit (at least {})", kMinFitPoints)};
  if (Status s = check_touched_points(model, points); !s) return s.error();
  std::vector<Parameter> ps = options.parameters;
  if (ps.empty()) {
    auto choice = fittable_parameters(model);
    if (!choice) return choice.error();
    ps = choice->fitted;
  }
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (std::find(chain.candidates().begin(), chain.candidates().end(), ps[i]) == chain.candidates().end())
      return Error{ErrorKind::invalid_argument, fmt::format("{} is not a parameter of arm '{}'", ps[i].name, model.name)};
    if (std::find(ps.begin(), ps.begin() + std::ptrdiff_t(i), ps[i]) != ps.begin() + std::ptrdiff_t(i))
      return Error{ErrorKind::invalid_argument, fmt::format("{} is asked for twice", ps[i].name)};
  }
  std::vector<Vector> qs;
  for (const TouchedPoint& p : points) qs.push_back(readings(p));
  const Eigen::Index P = Eigen::Index(ps.size());
  Vector x = Vector::Zero(P);

  // Identifiability: the Jacobian at the points, columns scaled to unit norm; its smallest
  // singular value against the largest, and the parameter that leads the direction it
  // belongs to.
  const Matrix j0 = jacobian(chain, qs, ps, x);
  const Vector norms = column_norms(j0);
  const double largest = norms.size() ? norms.maxCoeff() : 0;
  for (Eigen::Index c = 0; c < P; ++c)
    if (!(norms[c] > 1e-9 * largest))
      return Error{ErrorKind::invalid_argument,
                   fmt::format("the touched points cannot fit the {}: at their poses it does not move the tool "
                               "point; touch points with other joints moved",
                               ps[std::size_t(c)].name),
                   Unidentifiable{ps[std::size_t(c)], {}, 0.0}};
  const Matrix scaled = j0 * norms.cwiseInverse().asDiagonal();
  Eigen::JacobiSVD<Matrix> svd(scaled, Eigen::ComputeFullV);
  const Vector& sv = svd.singularValues();
  // Fewer equations than parameters: the missing singular values are zero.
  const double condition = sv.size() < P || sv[0] == 0 ? 0.0 : sv[sv.size() - 1] / sv[0];
  if (condition < options.min_condition) {
    const Vector v = svd.matrixV().col(P - 1);
    Eigen::Index lead = 0;
    v.cwiseAbs().maxCoeff(&lead);
    std::vector<Parameter> same_as;
    for (Eigen::Index c = 0; c < P; ++c)
      if (c != lead && std::abs(v[c]) >= 0.3 * std::abs(v[lead])) same_as.push_back(ps[std::size_t(c)]);
    const Parameter& p = ps[std::size_t(lead)];
    // The joints whose zeros are involved are the ones to move (a joint left at one position
    // hides the zeros and lengths around it); with lengths alone, every joint.
    std::string joints;
    std::vector<Parameter> involved = same_as;
    involved.insert(involved.begin(), p);
    for (const Parameter& q : involved)
      if (q.kind == ParameterKind::zero)
        joints += (joints.empty() ? "" : ", ") + model.joints[std::size_t(q.joint)].name;
    const std::string hint =
        joints.empty() ? "touch points spread wider, with every joint moved well between them"
                       : fmt::format("touch points with every joint moved well between them, {} above all", joints);
    // Joints that hardly moved between the points (less than a twentieth of their travel)
    // are the likeliest cause: say so.
    std::string still;
    for (int i = 0; i < chain.joint_count(); ++i) {
      double lo = qs.front()[i], hi = lo;
      for (const Vector& q : qs) lo = std::min(lo, q[i]), hi = std::max(hi, q[i]);
      const arm::JointModel& jm = model.joints[std::size_t(i)];
      if (hi - lo < (jm.limits.upper - jm.limits.lower) / 20)
        still += fmt::format("{}{} hardly moved between them (its readings span {})", still.empty() ? "; " : ", ", jm.name,
                             format_quantity(jm.dimension, hi - lo));
    }
    return Error{ErrorKind::invalid_argument,
                 fmt::format("the {} touched points cannot tell the {} apart{}{} (condition {:.2g}, at least {:.2g} "
                             "needed): {}{}",
                             points.size(), p.name, same_as.empty() ? "" : " from the ", names(same_as), condition,
                             options.min_condition, hint, still),
                 Unidentifiable{p, same_as, condition}};
  }
  if (points.size() < kMinFitPoints)
    return Error{ErrorKind::invalid_argument,
                 fmt::format("{} touched points; a fit of {} parameters needs at least {}, so that its residuals say "
                             "whether it holds",
                             points.size(), P, kMinFitPoints)};

  // Levenberg-Marquardt with Marquardt's scaling (the damping follows each parameter's
  // own curvature, so radians and metres need no common unit).
  FitResult result;
  Vector r = residual(chain, points, ps, x);
  double cost = r.squaredNorm();
  double lambda = 1e-3;
  Matrix j = j0;
  for (result.iterations = 0; result.iterations < options.max_iterations; ++result.iterations) {
    const Matrix a = j.transpose() * j;
    const Vector g = j.transpose() * r;
    Matrix damped = a;
    damped.diagonal() += lambda * a.diagonal();
    const Vector dx = -damped.ldlt().solve(g);
    const Vector x_new = x + dx;
    const Vector r_new = residual(chain, points, ps, x_new);
    const double cost_new = r_new.squaredNorm();
    if (cost_new < cost) {
      const bool done = cost - cost_new < 1e-14 * (1 + cost) || dx.norm() < 1e-12;
      x = x_new;
      r = r_new;
      cost = cost_new;
      lambda = std::max(lambda / 10, 1e-12);
      j = jacobian(chain, qs, ps, x);
      if (done) break;
    } else {
      lambda *= 10;
      if (lambda > 1e12) break;  // no step lowers the cost: at the minimum
    }
  }

  auto errors = [&](const Vector& xs) {
    std::vector<PointResidual> out;
    const Vector res = residual(chain, points, ps, xs);
    for (std::size_t k = 0; k < points.size(); ++k) {
      const Eigen::Vector3d e = res.segment<3>(3 * Eigen::Index(k));
      out.push_back(PointResidual{points[k].name, e, e.norm()});
    }
    return residual_report(std::move(out));
  };
  result.before = errors(Vector::Zero(P));
  result.after = errors(x);
  result.condition = condition;
  // One standard deviation from the residuals left: s^2 (J^T J)^-1.
  const double dof = double(3 * Eigen::Index(points.size()) - P);
  const double s2 = dof > 0 ? cost / dof : 0;
  const Matrix cov = (j.transpose() * j).ldlt().solve(Matrix::Identity(P, P)) * s2;
  for (Eigen::Index c = 0; c < P; ++c) {
    const Parameter& p = ps[std::size_t(c)];
    ParameterEstimate e{p, x[c], std::sqrt(std::max(0.0, cov(c, c))), 0};
    if (p.kind == ParameterKind::length) e.length = chain.length(p.origin) + x[c];
    result.estimates.push_back(e);
  }
  return result;
}

Result<ResidualReport> verify_fit(const arm::ArmModel& model, const FitResult& fit,
                                  std::span<const TouchedPoint> points) {
  if (points.empty()) return Error{ErrorKind::invalid_argument, "no touched points to verify"};
  if (Status s = check_touched_points(model, points); !s) return s.error();
  auto chain = CalibrationChain::make(model);
  if (!chain) return chain.error();
  const std::vector<Parameter> ps = fit.parameters();
  for (const Parameter& p : ps)
    if (std::find(chain->candidates().begin(), chain->candidates().end(), p) == chain->candidates().end())
      return Error{ErrorKind::invalid_argument, fmt::format("the fit's {} is not a parameter of arm '{}'", p.name, model.name)};
  Vector x(Eigen::Index(ps.size()));
  for (std::size_t k = 0; k < ps.size(); ++k) x[Eigen::Index(k)] = fit.estimates[k].correction;
  const Vector r = residual(*chain, points, ps, x);
  std::vector<PointResidual> out;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Eigen::Vector3d e = r.segment<3>(3 * Eigen::Index(k));
    out.push_back(PointResidual{points[k].name, e, e.norm()});
  }
  return residual_report(std::move(out));
}

CalibrationChanges changes_from_fit(const arm::ArmModel& model, const FitResult& fit) {
  CalibrationChanges c;
  for (const ParameterEstimate& e : fit.estimates) {
    if (e.parameter.kind == ParameterKind::zero)
      c.joints.push_back(JointChange{model.joints[std::size_t(e.parameter.joint)].name, false, e.correction, std::nullopt});
    else
      c.link_lengths.push_back(motion::OriginLength{e.parameter.origin, e.length});
  }
  return c;
}

}  // namespace armctl::calibration
