// Select lines in memory, for tests: records every level change and can tell an observer
// (e.g. a test thread playing the joints on the other side of a pty) about each edge.
#pragma once

#include <functional>
#include <mutex>
#include <vector>

#include "transport/select_lines.hpp"

namespace armctl::transport {

class FakeSelectLines final : public SelectLines {
 public:
  struct Edge {
    int joint;
    bool high;
  };
  using Observer = std::function<void(int joint, bool high)>;

  explicit FakeSelectLines(int count, Observer observer = {});

  int count() const override { return count_; }
  void set(int joint, bool high) override;  // throws ArmctlError(invalid_argument) if no such joint

  bool level(int joint) const;
  std::vector<Edge> edges() const;  // every change, in order (setting the same level is no edge)

 private:
  int count_;
  Observer observer_;
  mutable std::mutex mutex_;
  std::vector<bool> levels_;
  std::vector<Edge> edges_;
};

}  // namespace armctl::transport
