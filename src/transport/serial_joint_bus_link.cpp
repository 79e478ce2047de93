#include "transport/serial_joint_bus_link.hpp"

namespace armctl::transport {

SerialJointBusLink::SerialJointBusLink(std::unique_ptr<FdStream> port,
                                       std::unique_ptr<SelectLines> select, std::uint32_t baud)
    : port_(std::move(port)), select_(std::move(select)), baud_(baud) {}

SerialJointBusLink::~SerialJointBusLink() {
  // Never leave a joint selected (it would keep driving the shared TX line).
  for (int j = 1; j <= select_->count(); ++j) {
    try {
      select_->set(j, false);
    } catch (...) {  // NOLINT: a destructor must not throw; nothing better to do here
    }
  }
}

std::optional<std::uint8_t> SerialJointBusLink::read_byte(TimePoint deadline) {
  if (begin_ == end_) {
    begin_ = 0;
    end_ = port_->read(std::span<std::uint8_t>(buffer_), deadline);
    if (end_ == 0) return std::nullopt;
  }
  return buffer_[begin_++];
}

std::size_t SerialJointBusLink::drain() {
  std::size_t n = end_ - begin_;
  begin_ = end_ = 0;
  // Whatever the kernel already holds: read without waiting until nothing is left.
  for (;;) {
    const std::size_t got = port_->read(std::span<std::uint8_t>(buffer_), port_->clock().now());
    if (got == 0) break;
    n += got;
  }
  return n;
}

}  // namespace armctl::transport
