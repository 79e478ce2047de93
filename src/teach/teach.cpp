#include "teach/teach.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "core/atomic_file.hpp"

namespace armctl::teach {

Result<std::unique_ptr<LimpArm>> LimpArm::make(arm::Arm& arm) {
  std::unique_ptr<LimpArm> limp(new LimpArm(arm));
  if (auto s = arm.set_torque(false); !s) {
    // Some joints may have gone limp: the destructor puts them back under control.
    return s.error();
  }
  return limp;
}

LimpArm::~LimpArm() { (void)release(); }

Status LimpArm::release() {
  if (released_) return Ok{};
  released_ = true;
  // Both devices hold where the joints stand when control comes back (the xArm: a move to
  // the positions read; the joint bus: the loop takes the current count as its target).
  if (auto s = arm_.set_torque(true); !s) return s;
  // Let the hold reach the joints before anyone is told that torque is on.
  return arm_.device().idle(arm_.device().stream_latency() + arm_.device().stream_period(false));
}

files::Point point_at(const arm::ArmModel& model, const std::vector<double>& positions, std::string name) {
  files::Point p;
  p.name = std::move(name);
  for (std::size_t i = 0; i < positions.size() && i < model.joints.size(); ++i)
    p.joints.push_back({positions[i], model.joints[i].dimension});
  return p;
}

namespace {

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

std::string next_free_name(const files::PointsFile& file) {
  for (std::size_t n = 1;; ++n) {
    std::string name = fmt::format("p{}", n);
    if (file.find(name) == nullptr) return name;
  }
}

std::string describe(const arm::ArmModel& model, const std::vector<double>& q) {
  std::string out;
  for (std::size_t i = 0; i < q.size(); ++i)
    out += fmt::format("{}{} {}", i ? ", " : "", model.joints[i].name, arm::format_joint_value(model, int(i), q[i]));
  return out;
}

}  // namespace

const char* to_string(TeachEventKind kind) {
  switch (kind) {
    case TeachEventKind::started: return "started";
    case TeachEventKind::recorded: return "recorded";
    case TeachEventKind::replaced: return "replaced";
    case TeachEventKind::refused: return "refused";
    case TeachEventKind::finished: return "finished";
  }
  return "?";
}

Result<std::size_t> teach_points(arm::Arm& arm, const std::filesystem::path& points_path, const TeachIo& io) {
  files::PointsFile file;
  std::error_code ec;
  if (std::filesystem::exists(points_path, ec)) {
    auto read = files::read_points_file(points_path);
    if (!read) return read.error();
    file = std::move(read).value();
  }
  // A file that cannot be written is said now, not after the arm was moved by hand.
  if (auto s = check_writable(points_path); !s) return s.error();
  auto limp = LimpArm::make(arm);
  if (!limp) return limp.error();
  io.on_event({TeachEventKind::started,
               fmt::format("torque off: move the arm by hand; Enter records a point (type a name first, or "
                           "nothing for {}); end of input (Ctrl-D) or Ctrl-C ends",
                           next_free_name(file)),
               {}, {}, 0});
  std::size_t recorded = 0;
  while (auto line = io.next_line()) {
    std::string name = trimmed(*line);
    if (name.empty()) name = next_free_name(file);
    if (auto why = files::bad_name(name)) {
      io.on_event({TeachEventKind::refused, fmt::format("not recorded: {}; type another name", *why), name, {}, 0});
      continue;
    }
    auto state = arm.read();
    if (!state) return state.error();
    files::Point point = point_at(arm.model(), state->positions, name);
    bool replaced = false;
    for (auto& p : file.points)
      if (p.name == name) {
        p = point;
        replaced = true;
      }
    if (!replaced) file.points.push_back(point);
    if (auto s = files::write_points_file(points_path, file); !s) return s.error();
    ++recorded;
    io.on_event({replaced ? TeachEventKind::replaced : TeachEventKind::recorded,
                 fmt::format("{} {}: {}", replaced ? "replaced" : "recorded", name, describe(arm.model(), state->positions)),
                 name, state->positions, 0});
  }
  if (auto s = (*limp)->release(); !s) return s.error();
  io.on_event({TeachEventKind::finished,
               fmt::format("torque on, holding; {} point{} recorded in {}", recorded, recorded == 1 ? "" : "s",
                           points_path.string()),
               {}, {}, recorded});
  return recorded;
}

Result<motion::Recording> record_motion(arm::Arm& arm, const RecordOptions& options) {
  if (!(options.rate >= 1 && options.rate <= files::kRecordingMaxRate))
    return Error{ErrorKind::invalid_argument,
                 fmt::format("rate {} Hz: allowed is 1..{:g} Hz", options.rate, files::kRecordingMaxRate)};
  motion::Recording r;
  r.arm = arm.model().name;
  r.rate = options.rate;
  for (const auto& j : arm.model().joints) r.joints.push_back({j.name, j.dimension});
  const Duration period = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(1.0 / options.rate));
  // One read of every joint, timed before torque goes off: a rate the link cannot keep is
  // said now (the SCARA at 9600 baud reads seven joints in about 58 ms: 17 Hz at most), not
  // discovered as a recording at another rate than its header says.
  const TimePoint probe = arm.clock().now();
  if (auto first = arm.read(); !first) return first.error();
  const double read_s = std::chrono::duration<double>(arm.clock().now() - probe).count();
  if (read_s > std::chrono::duration<double>(period).count()) {
    const double most = std::floor(1.0 / (read_s * 1.1));
    return Error{ErrorKind::invalid_argument,
                 fmt::format("rate {:g} Hz is faster than this link allows: one read of every joint takes {:.0f} ms, "
                             "so at most {:g} Hz; ask for {:g} Hz or less (nothing recorded, torque not switched off)",
                             options.rate, read_s * 1e3, std::max(most, 1.0), std::max(most, 1.0))};
  }
  auto limp = LimpArm::make(arm);
  if (!limp) return limp.error();
  if (options.on_start) options.on_start();
  const TimePoint start = arm.clock().now();
  TimePoint next = start;
  TimePoint first_read = start;
  for (;;) {
    auto state = arm.read();
    if (!state) return state.error();
    motion::RecordingSample sample;
    if (r.samples.empty()) first_read = state->time;  // time 0: the first position read
    sample.time = std::chrono::duration<double>(state->time - first_read).count();
    if (!r.samples.empty() && !(sample.time > r.samples.back().time)) sample.time = r.samples.back().time + 1e-6;
    sample.positions = state->positions;
    r.samples.push_back(sample);
    if (options.on_sample) options.on_sample(sample);
    if (r.samples.size() >= files::kRecordingMaxSamples) break;
    if (options.done && options.done()) break;
    next += period;
    const TimePoint now = arm.clock().now();
    // Ends at the asked duration by the clock, also when reads ran late (it ran 5.83 s of 5).
    if (options.duration && std::max(next, now) - start > *options.duration) break;
    // A read that ran late (a busy host) starts the next period from now: no burst to catch up.
    if (now > next) next = now;
    if (next > now)
      if (auto s = arm.device().idle(next - now); !s) return s.error();
  }
  if (auto s = (*limp)->release(); !s) return s.error();
  return r;
}

}  // namespace armctl::teach
