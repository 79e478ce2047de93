// Structure-aware mutations for the config fuzzers: start from a real config document and
// apply a few edits chosen by the fuzzer (a value replaced by a boundary value or a value
// of another type, a key removed, an unknown key added, an array element copied or
// removed). Random text rarely gets past the JSON syntax; these edits reach every range
// check of the config parsers within seconds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace armctl::fuzz {

// Reads bytes front to back; past the end every value is zero.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  std::uint64_t u64() {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v = (v << 8) | byte();
    return v;
  }
  std::size_t index(std::size_t n) { return n == 0 ? 0 : (std::size_t(byte()) << 8 | byte()) % n; }
  bool empty() const { return pos_ >= size_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

inline std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "fuzz: cannot read %s\n", path.c_str());
    std::abort();
  }
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline nlohmann::json interesting_value(ByteReader& in) {
  using nlohmann::json;
  static const std::int64_t ints[] = {0,        1,        -1,        2,         6,
                                      7,        8,        255,       256,       299,
                                      300,      999,      1000,      1001,      3905,
                                      3906,     4095,     4096,      32767,     32768,
                                      -32768,   -32769,   65535,     65536,     100000,
                                      100001,   200000,   200001,    1000000,   1000001,
                                      2000000,  2000001,  20000000,  20000001,  50000000,
                                      50000001, std::numeric_limits<std::int64_t>::max(),
                                      std::numeric_limits<std::int64_t>::min()};
  static const double reals[] = {0.0,  -0.0,   1e-9,   1e-8,  0.001, 0.01,    0.5,
                                 5.0,  5.001,  60.0,   60.01, 100.0, 255.0,   255.01,
                                 1e300, -1e300, 5e-324, 1000.0, 1000.5, 3905.9, 0.0039};
  switch (in.byte() % 12) {
    case 0: return ints[in.index(std::size(ints))];
    case 1: return reals[in.index(std::size(reals))];
    case 2: return static_cast<std::int64_t>(in.u64());
    case 3: {
      double d;
      const std::uint64_t bits = in.u64();
      std::memcpy(&d, &bits, sizeof d);
      return d;  // NaN and infinities dump as null
    }
    case 4: return std::numeric_limits<std::uint64_t>::max() - in.byte();
    case 5: return nullptr;
    case 6: return in.byte() % 2 == 0;
    case 7: {
      static const char* strings[] = {"", "x", "Z", "SHOULDER", "0123456789012345678901234567890123456789"};
      return strings[in.index(std::size(strings))];
    }
    case 8: return json::array();
    case 9: return json::object();
    case 10: return json::array({ints[in.index(std::size(ints))], ints[in.index(std::size(ints))]});
    default: return static_cast<std::int64_t>(static_cast<std::int16_t>(in.u64()));
  }
}

// Applies 1..4 edits chosen by `in` to `doc`.
inline void apply_edits(nlohmann::json& doc, ByteReader& in) {
  using nlohmann::json;
  const int edits = 1 + in.byte() % 4;
  for (int e = 0; e < edits && !in.empty(); ++e) {
    const json flat = doc.flatten();
    if (flat.empty()) return;
    std::vector<std::string> leaves;
    for (const auto& item : flat.items()) leaves.push_back(item.key());
    const json::json_pointer leaf(leaves[in.index(leaves.size())]);
    const json::json_pointer parent = leaf.parent_pointer();
    json& p = doc[parent];
    switch (in.byte() % 6) {
      case 0: doc[leaf] = interesting_value(in); break;
      case 1:  // remove the key or element
        if (p.is_object()) p.erase(leaf.back());
        else if (p.is_array() && !p.empty()) p.erase(p.size() - 1);
        break;
      case 2:
        if (p.is_object()) p["unknown_" + std::to_string(in.byte())] = interesting_value(in);
        break;
      case 3:
        if (!parent.empty()) doc[parent] = interesting_value(in);
        break;
      case 4:  // copy an element of the enclosing array (a second joint, a third bound)
        if (!parent.empty() && doc[parent.parent_pointer()].is_array()) {
          json& a = doc[parent.parent_pointer()];
          const json copy = a[in.index(a.size())];
          a.push_back(copy);
        } else if (p.is_array()) {
          const json copy = p.empty() ? json(0) : p[in.index(p.size())];
          p.push_back(copy);
        }
        break;
      default: doc[leaf] = interesting_value(in); break;
    }
  }
}

// The text a config fuzz target parses: by the first byte, either the rest of the input as
// raw text, or `base` (a valid file) with edits chosen by the rest of the input.
inline std::string config_text_from(const std::uint8_t* data, std::size_t size,
                                    const std::string& base) {
  if (size == 0) return {};
  if (data[0] % 2 == 0) return std::string(reinterpret_cast<const char*>(data + 1), size - 1);
  auto doc = nlohmann::json::parse(base);
  ByteReader in(data + 1, size - 1);
  apply_edits(doc, in);
  return doc.dump();
}

}  // namespace armctl::fuzz
