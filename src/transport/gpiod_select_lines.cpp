#include "transport/gpiod_select_lines.hpp"

#include <gpiod.h>

#include <cerrno>
#include <cstring>

#include <fmt/core.h>

#include "core/error.hpp"

namespace armctl::transport {

namespace {
constexpr const char* kConsumer = "armctl-joint-select";
}

GpiodSelectLines::GpiodSelectLines(gpiod_chip* chip, std::string chip_name)
    : chip_(chip), chip_name_(std::move(chip_name)) {}

std::unique_ptr<GpiodSelectLines> GpiodSelectLines::open(const std::string& chip,
                                                         const std::vector<unsigned>& offsets) {
  if (offsets.empty() || offsets.size() > 7) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("{} select lines given: the joint bus has 1..7 joints", offsets.size()));
  }
  gpiod_chip* c = gpiod_chip_open_lookup(chip.c_str());
  if (c == nullptr) {
    const int err = errno;
    throw ArmctlError(ErrorKind::io,
                      fmt::format("open GPIO chip '{}': {} (errno {}); list chips with gpiodetect", chip,
                                  std::strerror(err), err));
  }
  std::unique_ptr<GpiodSelectLines> self(new GpiodSelectLines(c, chip));
  const unsigned available = gpiod_chip_num_lines(c);
  for (unsigned offset : offsets) {
    if (offset >= available) {
      throw ArmctlError(ErrorKind::invalid_argument,
                        fmt::format("GPIO chip '{}' has lines 0..{}: no line {}", chip, available - 1, offset));
    }
    gpiod_line* line = gpiod_chip_get_line(c, offset);
    if (line == nullptr || gpiod_line_request_output(line, kConsumer, 0) != 0) {
      const int err = errno;
      throw ArmctlError(ErrorKind::io,
                        fmt::format("request GPIO {} line {} as output: {} (errno {}); is it used by "
                                    "another program or driver? (gpioinfo {})",
                                    chip, offset, std::strerror(err), err, chip));
    }
    self->lines_.push_back(line);
    self->offsets_.push_back(offset);
  }
  return self;
}

GpiodSelectLines::~GpiodSelectLines() {
  for (gpiod_line* line : lines_) {
    gpiod_line_set_value(line, 0);  // leave every joint deselected
    gpiod_line_release(line);
  }
  gpiod_chip_close(chip_);
}

void GpiodSelectLines::set(int joint, bool high) {
  if (joint < 1 || joint > count()) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("select line for joint {} does not exist: joints are 1..{}", joint, count()));
  }
  const auto i = static_cast<std::size_t>(joint - 1);
  if (gpiod_line_set_value(lines_[i], high ? 1 : 0) != 0) {
    const int err = errno;
    throw ArmctlError(ErrorKind::io, fmt::format("set GPIO {} line {} {}: {} (errno {})", chip_name_,
                                                 offsets_[i], high ? "high" : "low", std::strerror(err), err));
  }
}

}  // namespace armctl::transport
