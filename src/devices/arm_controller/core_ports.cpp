#include "devices/arm_controller/core_ports.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <limits>

#include <fmt/core.h>

#include "core/error.hpp"

namespace armctl::arm_controller {

void LinkBusPort::set_select(std::uint8_t joint, bool high) {
  if (!high) link_.flush();
  link_.set_select(joint, high);
}

void LinkBusPort::send_byte(std::uint8_t byte) { link_.write(std::span(&byte, 1)); }

namespace {

std::string io_error(const std::filesystem::path& path, const char* doing) {
  return fmt::format("group memory {}: cannot {}: {}", path.string(), doing, std::strerror(errno));
}

}  // namespace

FileGroupMemory::FileGroupMemory(std::optional<std::filesystem::path> path, std::uint32_t size)
    : bytes_(size, 0xFF) {
  if (!path) return;
  fd_ = ::open(path->c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NONBLOCK, 0644);
  if (fd_ < 0) throw ArmctlError(ErrorKind::io, io_error(*path, "open"));
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    throw ArmctlError(ErrorKind::invalid_config,
                      fmt::format("group memory {}: not a regular file; move it away to start with no groups",
                                  path->string()));
  }
  const off_t length = ::lseek(fd_, 0, SEEK_END);
  if (length == 0) {
    // A new memory: blank, written whole once so every later write is one byte in place.
    if (::pwrite(fd_, bytes_.data(), bytes_.size(), 0) != static_cast<ssize_t>(bytes_.size())) {
      const std::string e = io_error(*path, "write");
      ::close(fd_);
      throw ArmctlError(ErrorKind::io, e);
    }
    return;
  }
  if (length != static_cast<off_t>(size)) {
    ::close(fd_);
    throw ArmctlError(ErrorKind::invalid_config,
                      fmt::format("group memory {}: {} bytes, expected {} (a file the arm controller "
                                  "wrote); move it away to start with no groups",
                                  path->string(), static_cast<long long>(length), size));
  }
  if (::pread(fd_, bytes_.data(), bytes_.size(), 0) != static_cast<ssize_t>(bytes_.size())) {
    const std::string e = io_error(*path, "read");
    ::close(fd_);
    throw ArmctlError(ErrorKind::io, e);
  }
}

FileGroupMemory::~FileGroupMemory() {
  if (fd_ >= 0) ::close(fd_);
}

void FileGroupMemory::write(std::uint32_t address, std::uint8_t value) {
  if (fd_ >= 0 && ::pwrite(fd_, &value, 1, address) != 1)
    throw ArmctlError(ErrorKind::io, fmt::format("group memory: cannot write byte {}: {}", address, std::strerror(errno)));
  bytes_[address] = value;
}

std::vector<controller::JointSetup> core_joint_setups(const ControllerConfig& config) {
  if (config.joints.size() > controller::ControllerCore::max_joints)
    throw ArmctlError(ErrorKind::invalid_config,
                      fmt::format("arm_controller: {} joints; the core drives at most {}", config.joints.size(),
                                  int{controller::ControllerCore::max_joints}));
  auto fits = [](const ControllerJointConfig& j, const char* what, double value, double lo, double hi) {
    if (value < lo || value > hi)
      throw ArmctlError(ErrorKind::invalid_config,
                        fmt::format("arm_controller joint {} ({}): {} {} does not fit the core (allowed {}..{})",
                                    j.number, j.name, what, value, lo, hi));
    return value;
  };
  constexpr double kI16Min = std::numeric_limits<std::int16_t>::min(), kI16Max = std::numeric_limits<std::int16_t>::max();
  std::vector<controller::JointSetup> setups;
  for (const ControllerJointConfig& j : config.joints) {
    controller::JointSetup s{};
    s.number = j.number;
    s.clicks_at_0 = static_cast<std::int16_t>(fits(j, "clicks at position 0", j.map.to_clicks(0), kI16Min, kI16Max));
    s.clicks_at_1000 =
        static_cast<std::int16_t>(fits(j, "clicks at position 1000", j.map.to_clicks(1000), kI16Min, kI16Max));
    s.soft_min = j.soft_min;
    s.soft_max = j.soft_max;
    s.max_speed_cps = static_cast<std::uint16_t>(fits(j, "max_speed_cps", j.max_speed_cps, 1, 65535));
    s.max_accel_cps2 = static_cast<std::uint32_t>(fits(j, "max_accel_cps2", j.max_accel_cps2, 1, 4294967295.0));
    s.zone = j.zone_clicks;
    setups.push_back(s);
  }
  return setups;
}

}  // namespace armctl::arm_controller
