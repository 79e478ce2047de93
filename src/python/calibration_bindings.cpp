// armctl.Calibration: the guided calibration's engine (calibration/calibration_session.hpp)
// for Python, made by Arm.calibration() and used as a context manager. Every step is the
// engine's; results are plain dicts (calibration/calibration_json.hpp, the same fields the
// HTTP API answers), errors armctl.Error. Nothing is written until confirm(); a block left
// without it (an exception, Ctrl-C, a return) writes nothing (docs/calibration.md "Python").
// Each call takes the arm's turn like any Arm call (DeviceGate); once the Arm is closed every
// call raises, so the engine's arm is never used after it is gone.
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <fmt/core.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "calibration/calibration_json.hpp"
#include "calibration/rc_servo_bus.hpp"
#include "calibration/touch_sheet.hpp"
#include "core/miscalibration.hpp"
#include "python_support.hpp"

namespace armctl::python {

namespace {

using JointArg = std::variant<int, std::string>;

// A JSON value as the Python value json.loads makes of it (dicts, lists, floats, None).
py::object to_python(const nlohmann::json& value) { return py::module_::import("json").attr("loads")(value.dump()); }

template <typename T>
T must_py(Result<T> r) {
  if (!r) raise(r.error());
  return std::move(r).value();
}
void must_py(Status s) {
  if (!s) raise(s.error());
}

}  // namespace

class PyCalibration {
 public:
  PyCalibration(arm::Arm& arm, DeviceGate& gate, robot_commands::Client* board, bool servo_offsets) : gate_(gate) {
    if (board) servos_ = std::make_unique<calibration::RcServoBus>(*board);
    calibration::SessionOptions options;
    options.servo_offsets = servo_offsets;
    session_ = std::make_unique<calibration::CalibrationSession>(arm, servos_.get(), options);
  }

  // A joint as Python names it: its index (0-based, the model's order) or its name.
  int joint(const JointArg& j) {
    const arm::ArmModel& m = s().model();
    if (const int* i = std::get_if<int>(&j)) {
      if (*i < 0 || *i >= m.joint_count())
        raise(ErrorKind::invalid_argument, fmt::format("joint {}: allowed an index 0..{} or a name", *i, m.joint_count() - 1));
      return *i;
    }
    const std::string& name = std::get<std::string>(j);
    if (auto i = m.find_joint(name)) return *i;
    std::string names;
    for (const auto& x : m.joints) names += (names.empty() ? "" : ", ") + x.name;
    raise(ErrorKind::invalid_argument, fmt::format("joint '{}': allowed an index 0..{} or a name ({})", name, m.joint_count() - 1, names));
  }

  // Runs `f` in the arm's turn with the GIL released.
  template <typename F>
  auto step(F&& f) {
    s();
    const auto turn = gate_.enter();
    return released(std::forward<F>(f));
  }

  void end() { session_.reset(); }
  // Results in SI, as every armctl.Arm call gives them.
  calibration::JsonValues si() { return {s().model(), calibration::Units::si}; }
  calibration::CalibrationSession& s() {
    if (!session_) raise(ErrorKind::invalid_argument, "this calibration session has ended (its with block was left)");
    return *session_;
  }

  static void define(py::module_& m);

 private:
  DeviceGate& gate_;
  std::unique_ptr<calibration::RcServoBus> servos_;
  std::unique_ptr<calibration::CalibrationSession> session_;
};

py::object make_calibration(arm::Arm& arm, DeviceGate& gate, robot_commands::Client* board, bool servo_offsets) {
  return py::cast(std::make_unique<PyCalibration>(arm, gate, board, servo_offsets));
}

void PyCalibration::define(py::module_& m) {
  using namespace pybind11::literals;
  using C = PyCalibration;
  namespace cal = calibration;
  py::class_<C>(m, "Calibration",
                "The guided calibration (docs/calibration.md), made by Arm.calibration(), for a with block. Each step\n"
                "may be run alone, again (the new answer replaces the old) or not at all; nothing is written until\n"
                "confirm(). Leaving the block without confirm() writes nothing.")
      .def("__enter__", [](C& c) -> C& { return c; }, py::return_value_policy::reference)
      .def("__exit__", [](C& c, py::object, py::object, py::object) {
        // Torque back on, as the terminal wizard leaves the arm; the pending answers go.
        if (c.session_) {
          try {
            (void)c.step([&] { return c.s().hold(); });
          } catch (const py::error_already_set&) {  // the Arm was closed first: nothing to hold
          }
        }
        c.end();
      })
      .def_property_readonly("joint_names", [](C& c) {
        std::vector<std::string> out;
        for (const auto& j : c.step([&]() -> const arm::ArmModel& { return c.s().model(); }).joints) out.push_back(j.name);
        return out;
      }, "The joints' names, the model's order (a step's `joint` is an index into it or a name).")
      .def("find", [](C& c) {
        auto r = must_py(c.step([&] { return c.s().find(); }));
        return to_python(cal::to_json(c.si(), r));
      }, "Step 1: what answers. {'devices': [{'id', 'joint', 'index', 'answers', 'position'}], 'silent': [ids], 'text'}.")
      .def("set_servo_id", [](C& c, int id) { must_py(c.step([&] { return c.s().set_servo_id(id); })); }, "id"_a,
           "Step 1 on the xArm: gives the ONE servo connected the ID `id` (the command reaches every servo on the bus:\n"
           "unplug the others first), then checks it answers alone.")
      .def("wiggle", [](C& c, const JointArg& j) {
        const int i = c.joint(j);
        must_py(c.step([&] { return c.s().wiggle(i); }));
      }, "joint"_a, "Step 2: moves the joint a few degrees (or millimetres) and back; ask the user which one moved.")
      .def("answer_which", [](C& c, const JointArg& j, const JointArg& moved) {
        const int i = c.joint(j), k = c.joint(moved);
        must_py(c.step([&] { return c.s().answer_which(i, k); }));
      }, "joint"_a, "moved"_a,
           "Step 2's answer: None when `moved` is `joint`; else armctl.Error naming both (the servo in that place has\n"
           "the wrong ID: step 1).")
      .def("nudge", [](C& c, const JointArg& j) {
        const int i = c.joint(j);
        must_py(c.step([&] { return c.s().nudge(i); }));
      }, "joint"_a, "Step 3: moves the joint a little in its positive direction (and leaves it there).")
      .def("answer_direction", [](C& c, const JointArg& j, bool went_as_shown) {
        const int i = c.joint(j);
        must_py(c.step([&] { return c.s().answer_direction(i, went_as_shown); }));
      }, "joint"_a, "went_as_shown"_a, "Step 3's answer: False flips the joint (pending until confirm()).")
      .def("release", [](C& c) { must_py(c.step([&] { return c.s().release(); })); },
           "Torque off: the joints move by hand (steps 4..7).")
      .def("hold", [](C& c) { must_py(c.step([&] { return c.s().hold(); })); }, "Torque on where the arm stands.")
      .def("read_joint", [](C& c, const JointArg& j) {
        const int i = c.joint(j);
        return must_py(c.step([&] { return c.s().read_joint(i); }));
      }, "joint"_a, "The joint's value now, as the arm file reads it before the pending changes (rad or m).")
      .def("mark_of", [](C& c, const JointArg& j) {
        const int i = c.joint(j);
        return cal::mark_of(c.s().model().joints[std::size_t(i)]);
      }, "joint"_a, "Where the joint is put for its zero step: 0, or a little inside its travel when 0 is an end of it.")
      .def("zero_here", [](C& c, const JointArg& j, std::optional<double> mark) {
        const int i = c.joint(j);
        const double at = mark.value_or(cal::mark_of(c.s().model().joints[std::size_t(i)]));
        return to_python(cal::to_json(c.si(), i, must_py(c.step([&] { return c.s().zero_here(i, at); }))));
      }, "joint"_a, "mark"_a = py::none(),
           "Step 4: the joint stands at its mark (`mark`: its true value there; default mark_of(joint), as the pictures show it).\n"
           "{'kind': 'file_zero'|'servo_offset', 'shift', 'servo_offset', 'text'}.")
      .def("limits", [](C& c, const JointArg& j, double end_a, double end_b) {
        const int i = c.joint(j);
        return to_python(cal::to_json(c.si(), i, must_py(c.step([&] { return c.s().limits(i, end_a, end_b); }))));
      }, "joint"_a, "end_a"_a, "end_b"_a,
           "Step 5: the joint's limits from its two ends (readings from read_joint, either order), with a margin;\n"
           "{'lower', 'upper'} in the new readings. Refused when they exclude the zero.")
      .def("gripper", [](C& c, double open, double closed) {
        return to_python(cal::to_json(c.si(), must_py(c.step([&] { return c.s().gripper(open, closed); }))));
      }, "open"_a, "closed"_a, "Step 6: the gripper's readings open and closed; {'open', 'closed'} in the new readings.")
      .def("sheet_points", [](C& c) {
        auto marks = must_py(cal::sheet_points(c.s().model(), cal::default_placement(c.s().model())));
        nlohmann::json out = nlohmann::json::array();
        for (const auto& p : marks) out.push_back(cal::to_json(c.si(), p));
        return to_python(out);
      }, "Step 7: the printed sheet's marks where the docs place it: [{'name', 'position': [x, y, z]}] (m).")
      .def("touch", [](C& c, const std::string& name, const std::vector<double>& position) {
        if (position.size() != 3)
          raise(ErrorKind::invalid_argument, fmt::format("position has {} values: give x, y, z in m", position.size()));
        auto point = must_py(cal::user_point(c.s().model(), name, Eigen::Vector3d(position[0], position[1], position[2])));
        return to_python(cal::to_json(c.si(), must_py(c.step([&] { return c.s().touch(point); }))));
      }, "name"_a, "position"_a,
           "Step 7: the tool point stands on the point `name` at `position` (x, y, z in m, base frame); the joints\n"
           "are read now. Touching a name again replaces it. {'name', 'position', 'joints'}.")
      .def("verify", [](C& c) { return to_python(cal::to_json(c.si(), must_py(c.step([&] { return c.s().verify(); })))); },
           "Step 7: the touched points' residuals on the arm as the pending changes have it:\n"
           "{'points': [{'name', 'error', 'distance'}], 'rms', 'max', 'worst'} (m).")
      .def("fit", [](C& c) { return to_python(cal::to_json(c.si(), must_py(c.step([&] { return c.s().fit(); })))); },
           "Step 8 (optional): zeros and link lengths fitted to the touched points (10..30), pending until confirm():\n"
           "{'estimates', 'before', 'after', 'condition', 'iterations'}; refused when ill-conditioned.")
      .def("forget", [](C& c, std::optional<JointArg> j) {
        if (!j) return c.step([&] { c.s().forget_all(); });
        const int i = c.joint(*j);
        c.step([&] { c.s().forget(i); });
      }, "joint"_a = py::none(), "Forgets one joint's pending answers, or all (joint None).")
      .def("changes", [](C& c) { return to_python(cal::to_json(c.si(), must_py(c.step([&] { return c.s().changes(); })))); },
           "What confirm() would write, checked as a whole:\n"
           "{'joints': [{'joint', 'flip', 'zero_shift', 'limits'}], 'servo_offsets', 'gripper', 'link_lengths', 'empty'}.")
      .def("describe", [](C& c) { return c.step([&] { return c.s().describe(); }); },
           "The pending changes for people, one line each.")
      .def("confirm", [](C& c) {
        const arm::ArmModel written = must_py(c.step([&] { return c.s().confirm(); }));
        c.end();
        return to_python(cal::written_json(written));
      }, "Writes the pending changes: servo offsets, then the arm file in one atomic replacement with the previous\n"
         "file kept beside it. {'file', 'previous'}. The session ends; the Arm drives with the new file from now on\n"
         "(arm.calibration() again starts from it).");
}

// armctl._armctl.testing.miscalibration: what `sim?miscal=SEED` does wrong (docs/simulator.md
// "Mis-assembled simulators"), for tests that answer the wizard as a user who sees the
// physical arm would. The same pure function the simulators apply; not part of the API.
void define_testing(py::module_& m) {
  using namespace pybind11::literals;
  py::module_ t = m.def_submodule("testing", "For armctl's own tests: what the mis-assembled simulators do wrong.");
  t.def("miscalibration", [](const std::string& arm, std::uint32_t seed) {
    if (arm != "xarm" && arm != "scara")
      raise(ErrorKind::invalid_argument, fmt::format("arm '{}': allowed xarm or scara", arm));
    const Miscalibration truth = make_miscalibration(arm == "xarm" ? MiscalArm::xarm : MiscalArm::scara, seed);
    nlohmann::json joints = nlohmann::json::array(), links = nlohmann::json::array();
    for (std::size_t i = 0; i < truth.joints.size(); ++i)
      joints.push_back({{"id", i + 1}, {"zero_shift", truth.joints[i].zero_shift}, {"flipped", truth.joints[i].flipped}});
    for (const LinkError& l : truth.links) links.push_back({{"joint", l.joint}, {"error_mm", l.error_mm}});
    nlohmann::json duplicate = nullptr;
    if (truth.duplicate) duplicate = {{"place", truth.duplicate->place}, {"answers_as", truth.duplicate->answers_as}};
    return to_python({{"pivot", truth.pivot}, {"joints", joints}, {"links", links}, {"duplicate", duplicate}});
  }, "arm"_a, "seed"_a,
        "{'pivot', 'joints': [{'id', 'zero_shift', 'flipped'}] (device units, by device ID), 'links', 'duplicate'};\n"
        "true = pivot + (flipped ? -1 : 1) * (device - pivot) + zero_shift.");
}

void define_calibration(py::module_& m) {
  PyCalibration::define(m);
  define_testing(m);
}

}  // namespace armctl::python
