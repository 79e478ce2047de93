#include "core/config_files.hpp"

#include <cstdlib>
#include <string>
#include <system_error>

namespace armctl {

std::filesystem::path find_config_file(std::string_view name) {
  const std::filesystem::path file{std::string(name)};
  std::error_code ec;
  if (const char* dir = std::getenv("ARMCTL_CONFIG_DIR"); dir != nullptr && *dir != '\0') {
    if (std::filesystem::exists(std::filesystem::path(dir) / file, ec)) {
      return std::filesystem::path(dir) / file;
    }
  }
  // The source tree first: a build (and its tests) must use the configs it was built with,
  // not an older installed copy.
  const std::filesystem::path source = std::filesystem::path(ARMCTL_SOURCE_CONFIG_DIR) / file;
  if (std::filesystem::exists(source, ec)) return source;
  const std::filesystem::path installed = std::filesystem::path(ARMCTL_INSTALLED_CONFIG_DIR) / file;
  if (std::filesystem::exists(installed, ec)) return installed;
  return source;
}

}  // namespace armctl
