#include "devices/robot_commands/arrival.hpp"

#include <algorithm>
#include <cstdlib>

#include <fmt/core.h>

namespace armctl::robot_commands {

bool ArrivalReport::all_arrived() const {
  return std::all_of(servos.begin(), servos.end(), [](const ServoArrival& s) { return s.arrived; });
}

std::vector<ServoArrival> ArrivalReport::missed() const {
  std::vector<ServoArrival> out;
  for (const auto& s : servos)
    if (!s.arrived) out.push_back(s);
  return out;
}

Result<ArrivalReport> wait_until_arrived(Client& client, const std::vector<ServoTarget>& targets,
                                         TimePoint deadline, const ArrivalOptions& options) {
  if (options.tolerance < 0 || options.tolerance > static_cast<int>(rc::kPositionMax)) {
    return Error{ErrorKind::invalid_argument,
                 fmt::format("arrival tolerance {} is out of range (allowed 0..{} servo units)",
                             options.tolerance, rc::kPositionMax)};
  }
  if (options.poll_period <= Duration::zero()) {
    return Error{ErrorKind::invalid_argument, "arrival poll period must be longer than zero"};
  }
  ArrivalReport report;
  std::vector<std::uint8_t> ids;
  for (const auto& t : targets) {
    report.servos.push_back(ServoArrival{t.servo, t.position, 0, false});
    ids.push_back(t.servo);
  }
  const TimePoint start = client.clock().now();
  if (ids.empty()) return report;
  if (options.not_before > start) {
    if (auto pumped = client.pump_events(options.not_before); !pumped) return pumped.error();
  }
  std::vector<std::optional<std::int16_t>> previous(ids.size());
  for (;;) {
    auto positions = client.read_positions(ids);
    if (!positions) return positions.error();
    for (std::size_t i = 0; i < ids.size(); ++i) {
      ServoArrival& s = report.servos[i];
      s.position = (*positions)[i].position;  // read_positions answers in the order asked
      const bool at_rest = previous[i] && std::abs(int{s.position} - int{*previous[i]}) <= kSettledBand;
      s.arrived = !s.target || s.position == *s.target ||
                  (at_rest && std::abs(int{s.position} - int{*s.target}) <= options.tolerance);
      previous[i] = s.position;
    }
    const TimePoint now = client.clock().now();
    report.elapsed = now - start;
    if (report.all_arrived() || now >= deadline) return report;
    // Waiting on the link (not sleeping) keeps notifications flowing and lets simulated
    // links advance their simulated time.
    if (auto pumped = client.pump_events(std::min(deadline, now + options.poll_period)); !pumped)
      return pumped.error();
  }
}

}  // namespace armctl::robot_commands
