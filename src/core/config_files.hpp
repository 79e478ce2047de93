// Where armctl finds its default config files (config/xarm.arm.json, config/scara.arm.json):
// $ARMCTL_CONFIG_DIR if set, then the source tree this binary was built from, then the
// installed copy (make install puts them in <prefix>/share/armctl).
#pragma once

#include <filesystem>
#include <string_view>

namespace armctl {

// The first of those places that holds `name`; if none does, the source-tree path, so that
// the error that follows names a concrete file.
std::filesystem::path find_config_file(std::string_view name);

}  // namespace armctl
