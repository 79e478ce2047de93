#include "apps/armctl/motion_trace.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <chrono>
#include <cstring>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "core/error.hpp"

namespace armctl::cli {

namespace {

// Fine enough that a blended corner of the demo's squares (a 5 mm zone at 40 mm/s) is drawn
// round, coarse enough that a minute of motion stays a few thousand rows.
constexpr double kPlanStep = 0.020;  // s of nominal time

Eigen::Vector3d tool_mm(const arm::Arm& arm, const std::vector<double>& joints) {
  return arm.forward(arm.chain_of(joints)).position * 1e3;
}

}  // namespace

CLI::Validator trace_file_check() {
  return CLI::Validator([](const std::string& v) { return v.empty() ? std::string("a file name is needed") : std::string(); },
                        "FILE");
}

MotionTrace::MotionTrace(const std::string& path) : path_(path) {
  if (path_.empty()) throw ArmctlError(ErrorKind::invalid_argument, "--trace needs a file name");
  file_ = std::fopen(path_.c_str(), "w");
  if (!file_)
    throw ArmctlError(ErrorKind::io, fmt::format("--trace {}: cannot write it: {}", path_, std::strerror(errno)));
  check(std::fputs("kind,line,t_s,planned_x_mm,planned_y_mm,planned_z_mm,measured_x_mm,measured_y_mm,measured_z_mm\n",
                   file_));
}

MotionTrace::~MotionTrace() {
  if (file_) std::fclose(file_);
}

void MotionTrace::check(int result) {
  if (result < 0 || std::ferror(file_))
    throw ArmctlError(ErrorKind::io, fmt::format("--trace {}: writing failed: {}", path_, std::strerror(errno)));
}

void MotionTrace::add(const arm::Arm& arm, std::size_t line, const arm::PlannedMotion& motion,
                      const arm::MotionReport& report) {
  // PlannedMotion::sample fills vectors of every joint of the arm (it does not size them).
  const std::size_t n = std::size_t(arm.model().joint_count());
  std::vector<double> q(n), v(n), a(n);
  // The plan up to where the motion ended (all of it, unless it was stopped part way).
  const double until = std::clamp(report.t_reached, 0.0, motion.duration);
  const int steps = std::max(1, static_cast<int>(std::ceil(until / kPlanStep)));
  for (int k = 0; k <= steps; ++k) {
    const double t = until * k / steps;
    motion.sample(t, q, v, a);
    const Eigen::Vector3d p = tool_mm(arm, q);
    check(std::fprintf(file_, "plan,%zu,%.3f,%.3f,%.3f,%.3f,,,\n", line, t0_ + t, p.x(), p.y(), p.z()));
  }
  for (const auto& s : report.reads_log) {
    const Eigen::Vector3d p = tool_mm(arm, s.planned);
    const Eigen::Vector3d m = tool_mm(arm, s.measured);
    check(std::fprintf(file_, "read,%zu,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f\n", line,
                       t0_ + std::chrono::duration<double>(s.elapsed).count(), p.x(), p.y(), p.z(), m.x(), m.y(),
                       m.z()));
  }
  check(std::fflush(file_));
  t0_ += std::max(until, std::chrono::duration<double>(report.elapsed).count());
}

void MotionTrace::finish() {
  if (!file_) return;
  std::FILE* f = file_;
  file_ = nullptr;
  if (std::fclose(f) != 0)
    throw ArmctlError(ErrorKind::io, fmt::format("--trace {}: writing failed: {}", path_, std::strerror(errno)));
}

}  // namespace armctl::cli
