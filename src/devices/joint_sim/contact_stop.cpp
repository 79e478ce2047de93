#include "devices/joint_sim/contact_stop.hpp"

#include <cmath>
#include <limits>

namespace armctl::joint_sim {

namespace {
// Travel without end stops: the widest the hardware's stops can be.
constexpr EndStops kOpen{std::numeric_limits<std::int32_t>::min() / 2, std::numeric_limits<std::int32_t>::max() / 2};
}  // namespace

ContactStop::ContactStop(std::function<bool(std::span<const double>)> touches, std::vector<JointHardware*> joints)
    : touches_(std::move(touches)) {
  for (JointHardware* hw : joints) joints_.push_back(Joint{hw, hw ? hw->params().end_stops : std::nullopt, 0, 1});
  free_.assign(joints_.size(), 0.0);
}

void ContactStop::hold(Joint& j, double at, int direction) {
  const EndStops own = j.own.value_or(kOpen);
  j.held = direction;
  j.hardware->set_end_stops(direction > 0 ? EndStops{own.min_clicks, std::int32_t(std::floor(at))}
                                          : EndStops{std::int32_t(std::ceil(at)), own.max_clicks});
}

void ContactStop::let_go(Joint& j) {
  j.held = 0;
  j.hardware->set_end_stops(j.own.value_or(kOpen));
}

void ContactStop::check() {
  std::vector<double> now(joints_.size(), 0.0);
  for (std::size_t i = 0; i < joints_.size(); ++i)
    if (joints_[i].hardware) now[i] = joints_[i].hardware->position_clicks();
  if (!touches_(now)) {
    free_ = now;
    was_free_ = true;
    // A held joint goes on once a step further no longer touches (the others moved away).
    for (std::size_t i = 0; i < joints_.size(); ++i) {
      Joint& j = joints_[i];
      if (j.held == 0) continue;
      std::vector<double> further = now;
      further[i] += j.held * j.probe;
      if (!touches_(further)) let_go(j);
    }
    return;
  }
  // An arm already touching (started there, turned there by hand) is let move: which way is
  // out is not for the joints to judge.
  if (!was_free_) return;
  // The joints whose own motion since the last free check makes it touch are held where they
  // were then; if none does alone, every joint that moved (together they touch).
  bool any = false;
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    Joint& j = joints_[i];
    if (!j.hardware || now[i] == free_[i]) continue;
    std::vector<double> alone = free_;
    alone[i] = now[i];
    if (!touches_(alone)) continue;
    j.probe = std::max(1.0, std::abs(now[i] - free_[i]));
    hold(j, free_[i], now[i] > free_[i] ? 1 : -1);
    any = true;
  }
  if (any) return;
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    Joint& j = joints_[i];
    if (!j.hardware || now[i] == free_[i]) continue;
    j.probe = std::max(1.0, std::abs(now[i] - free_[i]));
    hold(j, free_[i], now[i] > free_[i] ? 1 : -1);
  }
}

}  // namespace armctl::joint_sim
