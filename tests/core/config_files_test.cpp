#include "core/config_files.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace armctl {
namespace {

TEST(ConfigFiles, DefaultsComeFromTheSourceTree) {
  ::unsetenv("ARMCTL_CONFIG_DIR");
  const auto path = find_config_file("scara.arm.json");
  EXPECT_EQ(path, std::filesystem::path(ARMCTL_SOURCE_DIR) / "config" / "scara.arm.json");
  EXPECT_TRUE(std::filesystem::exists(path));
}

TEST(ConfigFiles, EnvironmentDirectoryWinsWhenItHoldsTheFile) {
  const auto dir = std::filesystem::temp_directory_path() / "armctl-config-files-test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "scara.arm.json") << "{}";
  ::setenv("ARMCTL_CONFIG_DIR", dir.c_str(), 1);
  EXPECT_EQ(find_config_file("scara.arm.json"), dir / "scara.arm.json");
  // A file the directory lacks still comes from the source tree.
  EXPECT_EQ(find_config_file("xarm.arm.json"),
            std::filesystem::path(ARMCTL_SOURCE_DIR) / "config" / "xarm.arm.json");
  ::unsetenv("ARMCTL_CONFIG_DIR");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace armctl
