// The simulated arm meets what stands around it (`armctl sim scara --scene`): a joint whose
// motion makes the arm touch an obstacle is held there by an end stop on that side (the
// hardware's inelastic stop: it stalls, its controller still driving it), so that the host's
// stall protection and following-error checks can be tested end to end. Checked every
// millisecond of simulated time with every joint at the same instant (SimBus::set_watch).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "devices/joint_sim/joint_hardware.hpp"

namespace armctl::joint_sim {

class ContactStop {
 public:
  // `touches`: whether the arm touches the obstacle with its joints at these positions
  // (encoder clicks, one per select line: joint number - 1; 0 where no joint is).
  // `joints`: the hardware of each line (nullptr where no joint is), outliving this.
  ContactStop(std::function<bool(std::span<const double>)> touches, std::vector<JointHardware*> joints);

  // Every joint is at `now`: hold the ones that just moved the arm into the obstacle, let go
  // of held ones that no longer would.
  void check();

 private:
  struct Joint {
    JointHardware* hardware = nullptr;
    std::optional<EndStops> own;  // its own end stops (the config's)
    int held = 0;                 // +1 / -1: held against moving further up / down
    double probe = 1;             // clicks: how far past its hold it is tried for a way on
  };
  void hold(Joint& j, double at, int direction);
  void let_go(Joint& j);

  std::function<bool(std::span<const double>)> touches_;
  std::vector<Joint> joints_;
  std::vector<double> free_;  // where every joint was at the last check the arm touched nothing
  bool was_free_ = false;
};

}  // namespace armctl::joint_sim
