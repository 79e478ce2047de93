// Select lines on a Linux GPIO chip through libgpiod 1.6 (Debian 12): one output line per
// joint, requested LOW at open, driven LOW again and released at close. On a Raspberry Pi 4
// the header GPIOs are gpiochip0 (BCM numbers = line offsets); see
// docs/wiring-raspberry-pi.md (and the note on the Pi 5 there).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "transport/select_lines.hpp"

struct gpiod_chip;
struct gpiod_line;

namespace armctl::transport {

class GpiodSelectLines final : public SelectLines {
 public:
  // `chip`: a name ("gpiochip0"), path, label or number, as gpiod_chip_open_lookup accepts.
  // `offsets[i]` is the line offset for joint i+1. Throws ArmctlError (io naming the chip,
  // the offset and errno; invalid_argument for an offset the chip does not have).
  static std::unique_ptr<GpiodSelectLines> open(const std::string& chip,
                                                const std::vector<unsigned>& offsets);
  ~GpiodSelectLines() override;
  GpiodSelectLines(const GpiodSelectLines&) = delete;
  GpiodSelectLines& operator=(const GpiodSelectLines&) = delete;

  int count() const override { return static_cast<int>(lines_.size()); }
  void set(int joint, bool high) override;

 private:
  GpiodSelectLines(gpiod_chip* chip, std::string chip_name);
  gpiod_chip* chip_;
  std::string chip_name_;
  std::vector<gpiod_line*> lines_;
  std::vector<unsigned> offsets_;
};

}  // namespace armctl::transport
