// The dashboard's files, embedded in the binary at build time (src/web/CMakeLists.txt):
// every file under web/public/ at the same path below /, and each line of web/vendor.txt
// ("<url path> <path relative to web/>") from the npm packages. `armctl serve` needs
// nothing on disk.
#pragma once

#include <cstddef>
#include <span>
#include <string_view>

namespace armctl::web {

struct StaticAsset {
  const char* path;  // "/index.html", "/assets/vendor/three.module.js"
  const char* begin;
  const char* end;
  std::string_view data() const { return {begin, std::size_t(end - begin)}; }
};

// Every embedded file (the generated table).
std::span<const StaticAsset> static_assets();
// The file served at `path` ("/" is /index.html), or nullptr.
const StaticAsset* find_asset(std::string_view path);
// The Content-Type for a file name by its extension (application/octet-stream if unknown).
const char* content_type_for(std::string_view path);

}  // namespace armctl::web
