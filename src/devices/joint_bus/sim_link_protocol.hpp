// The sim link: a tiny stream protocol that carries a joint bus *link* (select edges and
// bytes, not transactions) over a unix socket between a master (SimLinkClient) and a
// long-lived simulated arm (`armctl sim scara`, SimLinkServer). The master's own
// transaction logic runs unchanged over it. Documented in docs/joint-bus-master.md.
//
// Every message is  TYPE(1) LEN(1) PAYLOAD(LEN).
//   master -> arm   'S' 2  joint(1..7) level(0|1)   set a select line
//                   'W' n  bytes                    bytes onto the master's TX
//                   'F' 0                           flush: answer 'f' once TX is on the wire
//   arm -> master   'H' 5  joints(1) baud(u32 LE)   hello, sent once on connect
//                   'R' n  bytes                    bytes that arrived on the master's RX
//                   'f' 0                           flush done
//                   'E' n  text                     the arm refused a message; it closes
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace armctl::joint_bus::sim_link {

enum class Type : std::uint8_t {
  select = 'S',
  write = 'W',
  flush = 'F',
  hello = 'H',
  received = 'R',
  flushed = 'f',
  error = 'E',
};

struct Message {
  Type type;
  std::vector<std::uint8_t> payload;
};

// Encodes one message; payloads longer than 255 bytes are split by the callers.
std::vector<std::uint8_t> encode(Type type, std::span<const std::uint8_t> payload = {});

// Splits a byte stream into messages. A byte that is no known TYPE is a protocol error:
// the stream cannot be resynchronised, so the peer is dropped.
class Parser {
 public:
  void push(std::span<const std::uint8_t> bytes);
  // The next complete message; nothing if incomplete. Sets error() on a bad TYPE.
  std::optional<Message> next();
  const std::optional<std::string>& error() const { return error_; }

 private:
  std::vector<std::uint8_t> buffer_;
  std::size_t begin_ = 0;
  std::optional<std::string> error_;
};

}  // namespace armctl::joint_bus::sim_link
