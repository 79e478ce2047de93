// Robot Commands over a byte stream (serial port, pty, socket): the serial frame form with
// a streaming receiver that resynchronises after garbage.
#pragma once

#include <memory>

#include "devices/robot_commands/rc_link.hpp"
#include "protocol/robot_commands/frame_receiver.hpp"
#include "transport/byte_stream.hpp"

namespace armctl::robot_commands {

class StreamLink final : public RcLink {
 public:
  // `baud`: the line's rate (a pty has none: the rate the board on it runs at).
  StreamLink(std::unique_ptr<transport::ByteStream> stream, std::string description, std::uint32_t baud = 9600);

  void send(const rc::Frame& frame) override;
  std::optional<rc::Frame> receive(TimePoint deadline) override;
  const Clock& clock() const override { return stream_->clock(); }
  std::string describe() const override { return description_; }
  std::size_t discarded() const override { return receiver_.discarded_bytes(); }
  Duration frame_time(std::size_t serial_bytes) const override { return wire_time(serial_bytes, baud_); }

  transport::ByteStream& stream() { return *stream_; }

 private:
  std::unique_ptr<transport::ByteStream> stream_;
  std::string description_;
  std::uint32_t baud_;
  rc::FrameReceiver receiver_;
};

}  // namespace armctl::robot_commands
