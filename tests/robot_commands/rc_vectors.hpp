// Loads ../shared/vectors/robot-commands.json (ARMCTL_VECTORS_DIR) for byte-exact tests.
#pragma once

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace armctl::rc::testing {

inline std::vector<std::uint8_t> parse_hex(const std::string& text) {
  std::vector<std::uint8_t> out;
  std::istringstream in(text);
  std::string byte;
  while (in >> byte) out.push_back(static_cast<std::uint8_t>(std::stoul(byte, nullptr, 16)));
  return out;
}

struct Vector {
  std::string name;
  bool host_to_board = true;
  std::uint8_t cmd = 0;
  std::vector<std::uint8_t> bytes;
};

struct Malformed {
  std::vector<std::uint8_t> bytes;
  std::string expect;
};

inline nlohmann::json load_vectors_json() {
  std::ifstream in(std::string(ARMCTL_VECTORS_DIR) + "/robot-commands.json");
  return nlohmann::json::parse(in);
}

inline std::vector<Vector> load_vectors() {
  std::vector<Vector> out;
  const auto json = load_vectors_json();  // kept alive: range-for over a temporary's member
  for (const auto& v : json.at("vectors")) {
    Vector x;
    x.name = v.at("name");
    x.host_to_board = v.at("direction") == "host->board";
    x.cmd = v.at("cmd");
    x.bytes = parse_hex(v.at("bytes"));
    out.push_back(x);
  }
  return out;
}

inline std::vector<Malformed> load_malformed() {
  std::vector<Malformed> out;
  const auto json = load_vectors_json();
  for (const auto& v : json.at("malformed")) {
    out.push_back({parse_hex(v.at("bytes")), v.at("expect")});
  }
  return out;
}

// The malformed case whose "expect" text starts with `prefix`.
inline Malformed malformed_case(const std::string& prefix) {
  for (auto& m : load_malformed()) {
    if (m.expect.rfind(prefix, 0) == 0) return m;
  }
  throw std::runtime_error("no malformed vector starting with " + prefix);
}

}  // namespace armctl::rc::testing
