#include "web/base64.hpp"

namespace armctl::web {

namespace {
constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

int value_of(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}
}  // namespace

std::string base64_encode(const std::vector<std::uint8_t>& bytes) {
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = std::uint32_t(bytes[i]) << 16 | (i + 1 < bytes.size() ? std::uint32_t(bytes[i + 1]) << 8 : 0) |
                            (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += kAlphabet[n >> 18 & 63];
    out += kAlphabet[n >> 12 & 63];
    out += i + 1 < bytes.size() ? kAlphabet[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[n & 63] : '=';
  }
  return out;
}

std::optional<std::vector<std::uint8_t>> base64_decode(std::string_view text) {
  std::vector<std::uint8_t> out;
  std::uint32_t bits = 0;
  int count = 0, padding = 0;
  for (char c : text) {
    if (c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
    if (c == '=') {
      ++padding;
      ++count;
      bits <<= 6;
    } else {
      const int v = value_of(c);
      if (v < 0 || padding) return std::nullopt;  // nothing but padding after padding
      bits = bits << 6 | std::uint32_t(v);
      ++count;
    }
    if (count == 4) {
      if (padding > 2) return std::nullopt;
      out.push_back(std::uint8_t(bits >> 16));
      if (padding < 2) out.push_back(std::uint8_t(bits >> 8));
      if (padding < 1) out.push_back(std::uint8_t(bits));
      bits = 0;
      count = 0;
      if (padding) padding = 3;  // the end: any further group is refused
    }
  }
  if (count != 0) return std::nullopt;
  return out;
}

}  // namespace armctl::web
