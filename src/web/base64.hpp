// Base64 (RFC 4648, with padding) for the .rob files the API carries inside JSON.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace armctl::web {

std::string base64_encode(const std::vector<std::uint8_t>& bytes);
// nullopt unless `text` is base64 (whitespace between groups is allowed).
std::optional<std::vector<std::uint8_t>> base64_decode(std::string_view text);

}  // namespace armctl::web
