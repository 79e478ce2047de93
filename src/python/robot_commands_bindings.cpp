// armctl.RobotCommands: the Robot Commands SDK client (devices/robot_commands/client.hpp) on
// any board URI, in device units, for scripts that speak to servos directly; the drop-in
// armctl.xarm is written on top of it. Every call validates before sending (armctl.Error,
// kind 'invalid_argument') and releases the GIL while it talks to the board. One connection
// serves several Python threads, one call at a time (DeviceGate): a request and its reply are
// never interleaved with another thread's.
#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/core.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "files/action_group_file.hpp"
#include "python_support.hpp"
#include "session/xarm_session.hpp"

namespace armctl::python {

namespace {

std::uint8_t servo_id(int id) {
  if (id < 1 || id > 254) raise(ErrorKind::invalid_argument, fmt::format("servo ID {} is not allowed: 1..254", id));
  return static_cast<std::uint8_t>(id);
}

std::vector<std::uint8_t> servo_ids(const std::vector<int>& ids) {
  std::vector<std::uint8_t> out;
  for (int id : ids) out.push_back(servo_id(id));
  return out;
}

class PyRobotCommands {
 public:
  PyRobotCommands(const std::string& device, int servo_count, double timeout) {
    if (!(timeout >= 0 && timeout <= 60))
      raise(ErrorKind::invalid_argument, fmt::format("timeout {} s is not allowed: 0 (the link's default) .. 60 s", timeout));
    session_ = must(released([&] { return session::open_xarm_session(device, servo_count, static_cast<int>(timeout * 1000)); }));
  }

  // Waits for the call another thread runs (a group_events between two of its turns), then
  // ends the board.
  void close() {
    const auto turn = gate_.close();
    released([&] {
      session_.reset();
      return 0;
    });
  }

  robot_commands::Client& client() {
    if (!session_) gate_.raise_closed();
    return *session_->client;
  }

  void move(const std::vector<std::pair<int, std::optional<int>>>& targets, int time_ms) {
    if (time_ms < 0 || time_ms > 30000)
      raise(ErrorKind::invalid_argument, fmt::format("time {} ms is not allowed: 0..30000 ms", time_ms));
    std::vector<robot_commands::ServoTarget> t;
    for (const auto& [id, position] : targets) {
      robot_commands::ServoTarget st;
      st.servo = servo_id(id);
      if (position) {
        if (*position < 0 || *position > 1000)
          raise(ErrorKind::invalid_argument,
                fmt::format("servo {} position {} is not allowed: 0..1000 (None keeps it)", id, *position));
        st.position = static_cast<std::uint16_t>(*position);
      }
      t.push_back(st);
    }
    auto& c = client();
    must(released([&] { return c.move(t, static_cast<std::uint16_t>(time_ms)); }));
  }

  std::vector<std::pair<int, int>> read_positions(const std::optional<std::vector<int>>& servos) {
    auto& c = client();
    const auto ids = servos ? servo_ids(*servos) : c.all_servos();
    auto r = must(released([&] { return c.read_positions(ids); }));
    std::vector<std::pair<int, int>> out;
    for (const auto& p : r) out.emplace_back(p.servo, p.position);
    return out;
  }

  void servos_off(const std::optional<std::vector<int>>& servos) {
    auto& c = client();
    const auto ids = servos ? servo_ids(*servos) : c.all_servos();
    must(released([&] { return c.servos_off(ids); }));
  }

  int battery_millivolts() {
    auto& c = client();
    return must(released([&] { return c.battery_millivolts(); }));
  }

  std::vector<std::pair<int, int>> read_offsets(const std::optional<std::vector<int>>& servos) {
    auto& c = client();
    const auto ids = servos ? servo_ids(*servos) : c.all_servos();
    auto r = must(released([&] { return c.read_offsets(ids); }));
    std::vector<std::pair<int, int>> out;
    for (const auto& p : r) out.emplace_back(p.servo, p.offset);
    return out;
  }

  void adjust_offset(int servo, int offset) {
    auto& c = client();
    const auto id = servo_id(servo);
    must(released([&] { return c.adjust_offset(id, offset); }));
  }

  void save_offsets(const std::optional<std::vector<int>>& servos) {
    auto& c = client();
    const auto ids = servos ? servo_ids(*servos) : c.all_servos();
    must(released([&] { return c.save_offsets(ids); }));
  }

  // BusServoInfoWrite with a new ID and the limits and LED settings read back first, so
  // that only the ID changes. The board sends it to every servo on the bus.
  void write_servo_id(int new_id) {
    const auto id = servo_id(new_id);
    auto& c = client();
    must(released([&]() -> Status {
      auto info = c.read_bus_servo_info();
      if (!info) return info.error();
      robot_commands::BusServoInfoWrite w;
      w.servo = id;
      w.position_min = info->position_min;
      w.position_max = info->position_max;
      w.millivolts_min = info->millivolts_min;
      w.millivolts_max = info->millivolts_max;
      w.temp_max = info->temp_max;
      w.led_status = info->led_status;
      w.led_warning = info->led_warning;
      return c.write_bus_servo_info(w);
    }));
  }

  void download_group(int group, const std::string& text) {
    if (group < 0 || group > 254) raise(ErrorKind::invalid_argument, fmt::format("group {} is not allowed: 0..254", group));
    const auto file = must(files::parse_action_group(text, "<text>"));
    auto& c = client();
    must(released([&] { return c.download_group(static_cast<std::uint8_t>(group), file.actions); }));
  }

  void run_group(int group, int times) {
    if (group < 0 || group > 254 || times < 0 || times > 65535)
      raise(ErrorKind::invalid_argument,
            fmt::format("group {} times {} is not allowed: group 0..254, times 0..65535 (0: forever)", group, times));
    auto& c = client();
    must(released([&] { return c.run_group(static_cast<std::uint8_t>(group), static_cast<std::uint16_t>(times)); }));
  }

  void stop_group() {
    auto& c = client();
    must(released([&] { return c.stop_group(); }));
  }

  void erase_group(int group) {
    if (group < 0 || group > 255) raise(ErrorKind::invalid_argument, fmt::format("group {} is not allowed: 0..255 (255: all)", group));
    auto& c = client();
    must(released([&] { return c.erase_group(static_cast<std::uint8_t>(group)); }));
  }

  void set_group_speed(int group, int percent) {
    if (group < 0 || group > 255 || percent < 0 || percent > 65535)
      raise(ErrorKind::invalid_argument,
            fmt::format("group {} speed {} % is not allowed: group 0..255 (255: all), percent 0..65535", group, percent));
    auto& c = client();
    must(released([&] {
      return c.set_group_speed(static_cast<std::uint8_t>(group), static_cast<std::uint16_t>(percent));
    }));
  }

  DeviceGate gate_{"RobotCommands connection"};  // before the session: it outlives it
  std::unique_ptr<session::XarmSession> session_;
};

// A bound call of PyRobotCommands: it takes its turn on the connection for its whole run.
template <typename R, typename... A>
auto in_turn(R (PyRobotCommands::*call)(A...)) {
  return [call](PyRobotCommands& self, A... args) -> R {
    const auto turn = self.gate_.enter();
    return (self.*call)(std::forward<A>(args)...);
  };
}

}  // namespace

namespace {

// Source: robot_commands::Client or arm::ActionGroups (clock, pump_events, next_event).
template <typename Source>
py::list events_of(DeviceGate& gate, const std::function<Source&()>& client, double timeout) {
  if (!(timeout >= 0 && timeout <= 3600))
    raise(ErrorKind::invalid_argument, fmt::format("timeout {} s is not allowed: 0..3600 s", timeout));
  const auto wait = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(timeout));
  constexpr Duration turn_length = std::chrono::milliseconds(50);
  std::optional<TimePoint> deadline;
  while (true) {
    const auto turn = gate.enter();
    auto& c = client();
    const TimePoint now = c.clock().now();
    if (!deadline) deadline = now + wait;
    must(released([&] { return c.pump_events(std::min(*deadline, now + turn_length)); }));
    if (c.clock().now() < *deadline) continue;
    py::list out;
    while (auto e = c.next_event()) {
      py::dict d;
      d["kind"] = std::string(robot_commands::to_string(e->kind));
      d["group"] = e->group ? py::object(py::int_(*e->group)) : py::object(py::none());
      d["count"] = e->count ? py::object(py::int_(*e->count)) : py::object(py::none());
      out.append(d);
    }
    return out;
  }
}

}  // namespace

py::list group_events(DeviceGate& gate, const std::function<robot_commands::Client&()>& client, double timeout) {
  return events_of(gate, client, timeout);
}
py::list group_events(DeviceGate& gate, const std::function<arm::ActionGroups&()>& groups, double timeout) {
  return events_of(gate, groups, timeout);
}

void define_robot_commands(py::module_& m) {
  using namespace py::literals;
  py::class_<PyRobotCommands>(
      m, "RobotCommands",
      "A Robot Commands board (an xArm, the emulated xArm, armctl's SCARA arm controller) in device\n"
      "units: servo IDs, positions 0..1000, times in ms. RobotCommands(device='sim', servo_count=6,\n"
      "timeout=0) opens the board URI ('sim' = an emulated xArm inside this process, 'hid',\n"
      "'hid:SERIAL', 'serial:/dev/ttyUSB0', a /dev path) with `servo_count` servos (7 on the arm\n"
      "controller); timeout 0 = the link's reply timeout. A reply that does not come in time raises\n"
      "armctl.Error (kind 'timeout'). Threads may share one: each request and its reply take their\n"
      "turn on the link. Use as a context manager to close it.")
      .def(py::init<const std::string&, int, double>(), "device"_a = "sim", "servo_count"_a = 6, "timeout"_a = 0.0)
      .def("close", &PyRobotCommands::close, "Closes the board (an embedded one ends), after the call another thread runs (group_events\n"
           "ends early).")
      .def("__enter__", [](PyRobotCommands& c) -> PyRobotCommands& { return c; }, py::return_value_policy::reference)
      .def("__exit__", [](PyRobotCommands& c, py::object, py::object, py::object) { c.close(); })
      .def_property_readonly(
          "servo_count",
          [](PyRobotCommands& c) {
            const auto turn = c.gate_.enter();
            return c.client().options().servo_count;
          },
          "how many servos (IDs 1..n) this connection addresses")
      .def("move", in_turn(&PyRobotCommands::move), "targets"_a, "time_ms"_a,
           "MultiServoMove: [(servo, position 0..1000 or None to keep), ...] over time_ms (0..30000).")
      .def("read_positions", in_turn(&PyRobotCommands::read_positions), "servos"_a = py::none(),
           "[(servo, position), ...] of the listed servos (default: all).")
      .def("servos_off", in_turn(&PyRobotCommands::servos_off), "servos"_a = py::none(),
           "Removes torque from the listed servos (default: all); the next move restores it.")
      .def("battery_millivolts", in_turn(&PyRobotCommands::battery_millivolts), "The board's supply voltage in mV.")
      .def("read_offsets", in_turn(&PyRobotCommands::read_offsets), "servos"_a = py::none(), "[(servo, offset), ...]")
      .def("adjust_offset", in_turn(&PyRobotCommands::adjust_offset), "servo"_a, "offset"_a,
           "Sets a servo's offset now (-125..125, lost at power-off).")
      .def("save_offsets", in_turn(&PyRobotCommands::save_offsets), "servos"_a = py::none(),
           "Keeps the current offsets across power-off.")
      .def("write_servo_id", in_turn(&PyRobotCommands::write_servo_id), "new_id"_a,
           "Gives the servo on the bus the ID `new_id` (1..254), its limits kept. BusServoInfoWrite reaches\n"
           "every servo on the bus: connect only the one to renumber.")
      .def("download_group", in_turn(&PyRobotCommands::download_group), "group"_a, "text"_a,
           "Downloads an action group written in armctl's group-file format (docs/action-groups.md).")
      .def("run_group", in_turn(&PyRobotCommands::run_group), "group"_a, "times"_a = 1,
           "Runs a stored action group `times` times (0: until stop_group).")
      .def("stop_group", in_turn(&PyRobotCommands::stop_group), "Stops the running action group.")
      .def("erase_group", in_turn(&PyRobotCommands::erase_group), "group"_a, "Erases a group (255: all).")
      .def("set_group_speed", in_turn(&PyRobotCommands::set_group_speed), "group"_a, "percent"_a,
           "Playback speed of a group in % (100 = as recorded; group 255: all).")
      .def(
          "group_events",
          [](PyRobotCommands& c, double timeout) {
            return group_events(c.gate_, [&]() -> robot_commands::Client& { return c.client(); }, timeout);
          },
          "timeout"_a = 0.0,
          "Action-group notifications received so far (and within `timeout` s): list of dicts\n"
          "{'kind': 'started'|'stopped'|'finished', 'group': int|None, 'count': int|None}.");
}

}  // namespace armctl::python
