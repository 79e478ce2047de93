#include "session/arm_session.hpp"

#include <optional>
#include <utility>

#include <fmt/core.h>

#include "core/printable.hpp"
#include "scene/scene.hpp"

#include "transport/device_uri_parts.hpp"

namespace armctl::session {

Result<arm::ArmModel> load_arm(const std::string& arm) { return arm::load_arm_model(arm::arm_file_path(arm)); }

namespace {

// May throw (a device's constructor): open_arm_session turns that into its error.
Result<std::unique_ptr<ArmSession>> open_device(arm::ArmModel model, const std::string& device,
                                                const SessionOptions& options) {
  const std::string uri = device.empty() ? "sim" : device;
  const std::string named = fmt::format("device \"{}\": ", printable(uri));
  auto parts = transport::split_uri(uri);
  if (!parts) return parts.error().prefixed(named);
  auto factory = find_device_kind(parts->kind);
  if (!factory) return factory.error().prefixed(named);
  auto opened = (**factory)(DeviceRequest{model, uri, std::move(parts).value(), options});
  if (!opened) return opened.error();
  auto s = std::make_unique<ArmSession>();
  s->connection = std::move(opened->connection);
  s->reconnects = opened->reconnects;
  s->paced = opened->paced;
  s->board = opened->board;
  s->arm = std::make_unique<arm::Arm>(std::move(model), std::move(opened->device));
  return s;
}

}  // namespace

Result<std::unique_ptr<ArmSession>> open_arm_session(const std::string& arm_name, const std::string& device,
                                                     const SessionOptions& options) {
  auto model = load_arm(arm_name);
  if (!model) return model.error();
  std::optional<scene::Scene> scene;
  if (!options.scene.empty() || options.fence || options.reduced_mode) {
    auto loaded = options.scene.empty() ? Result<scene::Scene>(scene::Scene{}) : scene::load_scene(options.scene);
    if (!loaded) return loaded.error();
    // --fence / --reduced-mode switch the scene's, or else the arm file's.
    loaded = arm::with_arm_limits(std::move(loaded).value(), *model);
    if (options.fence && loaded) loaded = scene::with_fence(*loaded, *options.fence);
    if (options.reduced_mode && loaded) loaded = scene::with_reduced_mode(*loaded, *options.reduced_mode);
    if (!loaded) return loaded.error();
    scene = std::move(loaded).value();
    // Checked against the arm before anything opens: a scene the arm cannot check is refused.
    auto checked = arm::ArmKinematics(*model).with_scene(*scene);
    if (!checked) return checked.error();
  }
  auto session = catch_error([&] { return open_device(std::move(model).value(), device, options); });
  if (session && scene) {
    if (auto ok = (*session)->arm->set_scene(std::move(*scene)); !ok) return ok.error();
  }
  return session;
}

}  // namespace armctl::session
