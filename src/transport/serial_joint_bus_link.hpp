// The real joint bus: a serial port (UART, USB-serial adapter, or a pty in tests) plus one
// select line per joint. Timeouts run on the steady clock with poll(); flush() is tcdrain,
// so select never drops while COMMAND/DATA bytes are still in the UART.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "transport/fd_stream.hpp"
#include "transport/joint_bus_link.hpp"
#include "transport/select_lines.hpp"

namespace armctl::transport {

class SerialJointBusLink final : public JointBusLink {
 public:
  // `port` is an open serial port (SerialPort::open configured at `baud`).
  SerialJointBusLink(std::unique_ptr<FdStream> port, std::unique_ptr<SelectLines> select,
                     std::uint32_t baud);
  ~SerialJointBusLink() override;

  int joint_count() const override { return select_->count(); }
  void set_select(int joint, bool high) override { select_->set(joint, high); }
  void write(std::span<const std::uint8_t> bytes) override { port_->write(bytes); }
  void flush() override { port_->drain(); }
  std::optional<std::uint8_t> read_byte(TimePoint deadline) override;
  std::size_t drain() override;
  const Clock& clock() const override { return port_->clock(); }
  std::uint32_t baud() const override { return baud_; }

 private:
  std::unique_ptr<FdStream> port_;
  std::unique_ptr<SelectLines> select_;
  std::uint32_t baud_;
  std::array<std::uint8_t, 64> buffer_{};
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
};

}  // namespace armctl::transport
