#include "transport/fake_select_lines.hpp"

#include <string>

#include "core/error.hpp"

namespace armctl::transport {

FakeSelectLines::FakeSelectLines(int count, Observer observer)
    : count_(count), observer_(std::move(observer)), levels_(static_cast<std::size_t>(count), false) {}

void FakeSelectLines::set(int joint, bool high) {
  if (joint < 1 || joint > count_) {
    throw ArmctlError(ErrorKind::invalid_argument, "select line for joint " + std::to_string(joint) +
                                                       " does not exist: joints are 1.." +
                                                       std::to_string(count_));
  }
  {
    std::lock_guard lock(mutex_);
    const auto i = static_cast<std::size_t>(joint - 1);
    if (levels_[i] == high) return;
    levels_[i] = high;
    edges_.push_back(Edge{joint, high});
  }
  if (observer_) observer_(joint, high);
}

bool FakeSelectLines::level(int joint) const {
  std::lock_guard lock(mutex_);
  return levels_.at(static_cast<std::size_t>(joint - 1));
}

std::vector<FakeSelectLines::Edge> FakeSelectLines::edges() const {
  std::lock_guard lock(mutex_);
  return edges_;
}

}  // namespace armctl::transport
