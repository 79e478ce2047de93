// Reading one JSON object of a config file strictly: every key must be known, every value
// in its range, and every error names the file, the key path and what is allowed
// ("scara-arm.json: joints[2].max_speed_cps: 90000 is outside the allowed range 1..50000").
// Errors are thrown as ArmctlError(invalid_config): config parsers run at start-up, before
// anything moves, and report the first problem found.
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>
#include <string_view>
#include <utility>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/printable.hpp"
#include "core/regular_file.hpp"
#include "core/strict_json.hpp"

namespace armctl::json_reader {

using json = nlohmann::json;

// Config files are a few kB: larger or deeper documents are refused before they cost time
// and memory (a 6 MB file nested 3 million levels deep took 10 s and 510 MB to fail).
inline constexpr std::uintmax_t kMaxConfigBytes = 1 << 20;
inline constexpr int kMaxConfigDepth = 32;

// Parses one config document; errors (invalid_config) start with `source`.
inline json parse_document(std::string_view text, const std::string& source) {
  if (text.size() > kMaxConfigBytes)
    throw ArmctlError(ErrorKind::invalid_config,
                      fmt::format("{}: {} bytes is larger than a config file may be (1 MiB)", printable(source), text.size()));
  Result<json> doc = parse_strict_json(text, kMaxConfigDepth);
  if (!doc) throw ArmctlError(ErrorKind::invalid_config, fmt::format("{}: {}", printable(source), doc.error().message));
  return std::move(doc).value();
}

// The text of a config file: a regular file of at most kMaxConfigBytes, checked before it is
// read (a directory, a FIFO, a huge or sparse file never is), without a leading UTF-8
// byte-order mark (read_text_file). `what` names it in errors.
inline std::string read_config_file(const std::filesystem::path& path, std::string_view what) {
  return read_text_file(path, what, kMaxConfigBytes).value();
}

// Reads one JSON object, refusing unknown keys; errors carry "<source>: <path>: ...".
class ObjectReader {
 public:
  ObjectReader(const std::string& source, const json& object, std::string path)
      : source_(source), object_(object), path_(std::move(path)) {
    if (!object_.is_object()) fail(path_, "must be an object");
  }

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    // The path holds the file's own keys and `what` may quote its values: printable() keeps
    // a key like "\x1b]0;owned\x07" from reaching the terminal as a control sequence.
    throw ArmctlError(ErrorKind::invalid_config,
                      fmt::format("{}: {}: {}", printable(source_), printable(path), printable(what)));
  }
  std::string at(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  const json* find(const std::string& key) {
    known_.insert(key);
    auto it = object_.find(key);
    return it == object_.end() ? nullptr : &*it;
  }
  const json& require(const std::string& key) {
    const json* v = find(key);
    if (v == nullptr) fail(at(key), "missing");
    return *v;
  }

  double number(const json& v, const std::string& path, double min, double max) const {
    if (!v.is_number()) fail(path, fmt::format("must be a number in {}..{}", min, max));
    double x = v.get<double>();
    if (!std::isfinite(x) || x < min || x > max)
      fail(path, fmt::format("{} is outside the allowed range {}..{}", x, min, max));
    return x;
  }
  std::int64_t integer(const json& v, const std::string& path, std::int64_t min,
                       std::int64_t max) const {
    if (!v.is_number_integer()) fail(path, fmt::format("must be a whole number in {}..{}", min, max));
    // Above INT64_MAX the value is stored unsigned and get<int64_t> would wrap it negative,
    // so the message would name a number the file does not contain.
    if (v.is_number_unsigned() && v.get<std::uint64_t>() > std::uint64_t(max))
      fail(path, fmt::format("{} is outside the allowed range {}..{}", v.get<std::uint64_t>(), min, max));
    auto x = v.get<std::int64_t>();
    if (x < min || x > max) fail(path, fmt::format("{} is outside the allowed range {}..{}", x, min, max));
    return x;
  }
  double number(const std::string& key, double min, double max) {
    return number(require(key), at(key), min, max);
  }
  std::int64_t integer(const std::string& key, std::int64_t min, std::int64_t max) {
    return integer(require(key), at(key), min, max);
  }
  // A two-element array [a, b] of whole numbers in min..max.
  std::pair<std::int64_t, std::int64_t> pair(const std::string& key, std::int64_t min,
                                             std::int64_t max) {
    const json& v = require(key);
    if (!v.is_array() || v.size() != 2)
      fail(at(key), fmt::format("must be an array of two whole numbers in {}..{}", min, max));
    return {integer(v[0], at(key) + "[0]", min, max), integer(v[1], at(key) + "[1]", min, max)};
  }

  // Refuses every key that was not read (except "comment").
  void finish() const {
    for (auto it = object_.begin(); it != object_.end(); ++it) {
      if (it.key() == "comment" || known_.count(it.key())) continue;
      std::string allowed;
      for (const auto& k : known_) allowed += (allowed.empty() ? "" : ", ") + k;
      fail(at(it.key()), fmt::format("unknown key (allowed here: comment, {})", allowed));
    }
  }

 private:
  const std::string& source_;
  const json& object_;
  std::string path_;
  std::set<std::string> known_;
};

}  // namespace armctl::json_reader
