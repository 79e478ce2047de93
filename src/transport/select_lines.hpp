// The joint bus select lines: one output per joint, active HIGH, idle LOW (spec "Wiring").
// Implementations: GpiodSelectLines (Linux GPIO character device via libgpiod) and
// FakeSelectLines (in memory, for tests).
#pragma once

namespace armctl::transport {

class SelectLines {
 public:
  virtual ~SelectLines() = default;
  virtual int count() const = 0;                // lines exist for joints 1..count()
  virtual void set(int joint, bool high) = 0;  // throws ArmctlError on failure
};

}  // namespace armctl::transport
