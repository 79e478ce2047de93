// The sim link stream decoder (devices/joint_bus/sim_link_protocol.hpp) on arbitrary bytes
// from the socket, pushed in chunks whose sizes the input chooses (so messages split at
// every place and the buffer compaction past 4 KiB runs). Checked against a reference
// reading of the format (TYPE LEN PAYLOAD; an unknown TYPE at a message boundary is a
// permanent error): the same messages, in order, byte for byte, then nothing; and every
// decoded message encodes back to exactly the bytes it came from.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>
#include <vector>

#include "devices/joint_bus/sim_link_protocol.hpp"

namespace {

namespace sl = armctl::joint_bus::sim_link;

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz_sim_link: %s\n", what);
  std::abort();
}

bool known(std::uint8_t t) {
  return t == 'S' || t == 'W' || t == 'F' || t == 'H' || t == 'R' || t == 'f' || t == 'E';
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  // Byte 0: chunk size seed; the stream is repeated so the 4 KiB compaction is reached.
  const std::size_t chunk_seed = data[0];
  std::vector<std::uint8_t> stream;
  const std::size_t repeat = size < 64 ? 1 : 1 + 8192 / size;
  for (std::size_t r = 0; r < repeat; ++r) stream.insert(stream.end(), data + 1, data + size);

  // Reference: the messages and where the stream goes bad.
  std::vector<std::pair<std::size_t, std::size_t>> expect;  // (offset, total length)
  bool expect_error = false;
  for (std::size_t p = 0;;) {
    if (stream.size() - p < 2) break;
    if (!known(stream[p])) {
      expect_error = true;
      break;
    }
    const std::size_t len = stream[p + 1];
    if (stream.size() - p < 2 + len) break;
    expect.emplace_back(p, 2 + len);
    p += 2 + len;
  }

  sl::Parser parser;
  std::size_t fed = 0, got = 0, step = 0;
  while (fed < stream.size()) {
    const std::size_t n = std::min<std::size_t>(stream.size() - fed, 1 + (chunk_seed * 31 + step * 7) % 700);
    ++step;
    parser.push(std::span<const std::uint8_t>(stream.data() + fed, n));
    fed += n;
    while (auto m = parser.next()) {
      check(got < expect.size(), "a message the stream does not contain");
      const auto [off, total] = expect[got];
      check(off + total <= fed, "a message before its bytes arrived");
      const std::vector<std::uint8_t> bytes = sl::encode(m->type, m->payload);
      check(bytes.size() == total &&
                std::equal(bytes.begin(), bytes.end(), stream.begin() + static_cast<std::ptrdiff_t>(off)),
            "message differs from its bytes");
      ++got;
    }
  }
  check(got == expect.size(), "messages lost");
  check(parser.error().has_value() == expect_error, "error reported iff an unknown TYPE");
  if (parser.error()) {
    check(parser.error()->find("allowed") != std::string::npos, "error names what is allowed");
    parser.push(std::span<const std::uint8_t>(data, size));
    check(!parser.next(), "no message after an error");
  }
  return 0;
}
