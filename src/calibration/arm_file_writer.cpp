#include "calibration/arm_file_writer.hpp"

#include <fmt/core.h>

#include "core/atomic_file.hpp"
#include "core/printable.hpp"

namespace armctl::calibration {

namespace {

// Arm files and URDFs are a few kB; this is far above any real one.
constexpr std::uintmax_t kMaxFileBytes = 4 << 20;

std::span<const std::uint8_t> bytes_of(const std::string& text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

Result<std::string> read_text(const std::filesystem::path& path, const char* what) {
  auto bytes = read_whole_file(path, kMaxFileBytes);
  if (!bytes) return bytes.error();
  if (!*bytes) return Error{ErrorKind::io, fmt::format("{} {} does not exist", what, printable(path.string()))};
  return std::string((*bytes)->begin(), (*bytes)->end());
}

}  // namespace

std::filesystem::path previous_file(const std::filesystem::path& arm_file) {
  std::filesystem::path p = arm_file;
  p += ".prev";
  return p;
}

Result<arm::ArmModel> write_calibration(const arm::ArmModel& model, const CalibrationChanges& changes) {
  if (model.file.empty()) return Error{ErrorKind::invalid_argument, "this arm model was not read from a file: nothing to write"};
  auto checked = check_changes(model, changes);
  if (!checked) return checked.error();
  // Refused before any work: a file that cannot be replaced, or no room for .prev.
  if (Status s = check_writable(model.file); !s) return s.error();
  const std::filesystem::path prev = previous_file(model.file);
  if (Status s = check_writable(prev); !s) return s.error();

  auto old_text = read_text(model.file, "arm file");
  if (!old_text) return old_text.error();
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(*old_text);
  } catch (const nlohmann::json::exception& e) {
    return Error{ErrorKind::invalid_config, fmt::format("{}: not valid JSON: {}", printable(model.file.string()), e.what())};
  }
  auto changed = apply_changes(std::move(doc), model, *checked);
  if (!changed) return changed.error();
  const std::string new_text = changed->dump(2) + "\n";

  // The whole new file must load, with its URDF, before it may replace the old one.
  auto urdf = read_text(model.urdf, "URDF");
  if (!urdf) return urdf.error();
  auto loaded = arm::parse_arm_model(new_text, model.file.string(), *urdf, model.urdf.string());
  if (!loaded)
    return Error{ErrorKind::invalid_argument,
                 fmt::format("the calibrated arm file would not load, so nothing was written: {}", loaded.error().message)};

  if (Status s = write_file_atomically(prev, bytes_of(*old_text)); !s) return s.error();
  if (Status s = write_file_atomically(model.file, bytes_of(new_text)); !s) return s.error();
  arm::ArmModel out = std::move(loaded).value();
  out.file = model.file;
  out.urdf = model.urdf;
  return out;
}

}  // namespace armctl::calibration
