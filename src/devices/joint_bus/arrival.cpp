#include "devices/joint_bus/arrival.hpp"

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <string>

#include <fmt/core.h>

namespace armctl::joint_bus {

namespace {

double seconds(Duration d) { return std::chrono::duration<double>(d).count(); }

std::string value_text(const std::optional<std::int16_t>& v) {
  return v ? std::to_string(*v) : std::string("unknown");
}

// The loop both waits share: `poll` performs one poll of one joint (true = arrived);
// `missing` names what a joint was waiting for, for the timeout message.
std::vector<JointArrival> poll_until(BusMaster& master, std::vector<JointArrival> rows,
                                     TimePoint deadline, const WaitOptions& options,
                                     const std::function<Result<bool>(JointArrival&)>& poll,
                                     const std::string& missing) {
  const TimePoint start = master.clock().now();
  const int allowed = std::max(1, options.failed_polls_allowed);
  const Duration period = std::max(options.poll_period, Duration{std::chrono::microseconds(100)});
  std::vector<int> failed_polls(rows.size(), 0);
  std::vector<bool> settled(rows.size(), false);
  for (;;) {
    bool pending = false;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (settled[i]) continue;
      JointArrival& row = rows[i];
      Result<bool> r = poll(row);
      if (r.ok()) {
        failed_polls[i] = 0;
        if (*r) {
          row.arrived = true;
          row.error.reset();
          row.after = master.clock().now() - start;
          settled[i] = true;
          continue;
        }
      } else if (++failed_polls[i] >= allowed) {
        row.error = r.error();
        row.after = master.clock().now() - start;
        settled[i] = true;
        continue;
      }
      pending = true;
    }
    if (!pending) return rows;
    const TimePoint now = master.clock().now();
    if (now >= deadline) break;
    master.idle_until(std::min(deadline, now + period));
  }
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (settled[i]) continue;
    JointArrival& row = rows[i];
    // Read both ends back so that the message says how far off the joint is.
    if (auto p = master.get_position(row.joint)) row.position = *p;
    if (!row.target)
      if (auto t = master.get_target(row.joint)) row.target = *t;
    row.after = master.clock().now() - start;
    row.error = Error{ErrorKind::timeout,
                      fmt::format("joint {}: not {} within {:.1f} s (position {}, target {})",
                                  row.joint, missing, seconds(deadline - start),
                                  value_text(row.position), value_text(row.target))};
  }
  return rows;
}

}  // namespace

std::vector<JointArrival> wait_until_reached(BusMaster& master, std::span<const int> joints,
                                             TimePoint deadline, const WaitOptions& options) {
  std::vector<JointArrival> rows;
  for (int j : joints) {
    JointArrival row;
    row.joint = j;
    rows.push_back(row);
  }
  return poll_until(
      master, std::move(rows), deadline, options,
      [&](JointArrival& row) { return master.check_target_reached(row.joint); }, "in its zone");
}

std::vector<JointArrival> wait_until_at(BusMaster& master, std::span<const JointTarget> targets,
                                        int tolerance, TimePoint deadline,
                                        const WaitOptions& options) {
  std::vector<JointArrival> rows;
  for (const auto& t : targets) {
    JointArrival row;
    row.joint = t.joint;
    row.target = t.position;
    rows.push_back(row);
  }
  if (tolerance < 0) {
    for (auto& row : rows)
      row.error = Error{ErrorKind::invalid_argument,
                        fmt::format("tolerance {} clicks is not allowed (0 or more)", tolerance)};
    return rows;
  }
  return poll_until(
      master, std::move(rows), deadline, options,
      [&](JointArrival& row) -> Result<bool> {
        auto p = master.get_position(row.joint);
        if (!p) return p.error();
        row.position = *p;
        return std::abs(int{*p} - int{*row.target}) <= tolerance;
      },
      fmt::format("within {} clicks of its target", tolerance));
}

bool all_arrived(std::span<const JointArrival> arrivals) {
  return std::all_of(arrivals.begin(), arrivals.end(),
                     [](const JointArrival& a) { return a.arrived; });
}

}  // namespace armctl::joint_bus
