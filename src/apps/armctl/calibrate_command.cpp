// armctl calibrate [--arm A] [--device URI] [--joint J] [STEP]
// The guided calibration (docs/calibration.md "The wizard"): a terminal adapter over the
// engine calibration::CalibrationSession, which runs every step and holds the answers. This
// file only prompts, checks what is typed and prints. Each step runs alone when named; every
// prompt takes r (redo), s (skip) and q (quit). Nothing is written until the user confirms the
// changes shown at the end; quitting, Ctrl-C, the end of input or an error write nothing.
#include <cstdlib>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "apps/armctl/commands.hpp"
#include "apps/armctl/serve_support.hpp"
#include "apps/armctl/stdin_lines.hpp"
#include "calibration/arm_file_writer.hpp"
#include "calibration/calibration_session.hpp"
#include "calibration/joint_pictures.hpp"
#include "calibration/rc_servo_bus.hpp"
#include "calibration/touch_sheet.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/must.hpp"
#include "core/quantity.hpp"
#include "session/arm_session.hpp"

namespace armctl::cli {

namespace {

const std::vector<std::string> kSteps{"find", "which", "direction", "zero", "limits", "gripper", "touch", "fit"};

struct CalibrateArgs {
  std::string arm = "xarm";
  std::string device;
  std::string joint;
  std::string step = "all";
  // --zero-in servo|file: an xArm joint's zero in the servo's own offset when it fits (the
  // default), or always in the arm file.
  std::string zero_in = "servo";
  std::string pictures;  // --pictures FILE: write the joints' pictures and stop
};

// The user quit (q) or the input ended: nothing is written.
struct Quit {
  std::string why;
};

class Terminal {
 public:
  Terminal(StdinLines& in, Interrupted& interrupted) : in_(in), interrupted_(interrupted) {}
  void say(const std::string& text) {
    fmt::print("{}", text);
    std::fflush(stdout);
  }
  // One answer; q, Ctrl-C and the end of input leave the wizard.
  std::string ask(const std::string& question) {
    say(question + " ");
    auto line = in_.next();
    if (interrupted_) throw ArmctlError(ErrorKind::device, "interrupted: nothing written");
    if (!line) throw Quit{"the input ended before the wizard finished"};
    std::string a = *line;
    while (!a.empty() && (a.back() == '\r' || a.back() == ' ')) a.pop_back();
    while (!a.empty() && a.front() == ' ') a.erase(0, 1);
    if (a == "q") throw Quit{"quit"};
    return a;
  }

 private:
  StdinLines& in_;
  Interrupted& interrupted_;
};

enum class Next { done, redo, skip };

// y/n with r and s; anything else is asked again, saying what is allowed.
std::optional<bool> yes_no(Terminal& t, const std::string& question, Next& next) {
  for (;;) {
    const std::string a = t.ask(question + " [y/n, r redo, s skip, q quit]");
    if (a == "y" || a == "yes") return true;
    if (a == "n" || a == "no") return false;
    if (a == "r") {
      next = Next::redo;
      return std::nullopt;
    }
    if (a == "s") {
      next = Next::skip;
      return std::nullopt;
    }
    t.say(fmt::format("'{}': allowed y, n, r (redo), s (skip), q (quit)\n", a));
  }
}

// Enter to go on, r, s.
Next enter(Terminal& t, const std::string& prompt) {
  for (;;) {
    const std::string a = t.ask(prompt + " [Enter, r redo, s skip, q quit]");
    if (a.empty()) return Next::done;
    if (a == "r") return Next::redo;
    if (a == "s") return Next::skip;
    t.say(fmt::format("'{}': allowed Enter, r (redo), s (skip), q (quit)\n", a));
  }
}

std::string value_text(const arm::JointModel& j, double si) {
  return j.dimension == Dimension::angle ? fmt::format("{:.2f} deg", si * 180 / 3.141592653589793)
                                         : fmt::format("{:.2f} mm", si * 1000);
}

class Wizard {
 public:
  Wizard(calibration::CalibrationSession& s, Terminal& t, std::vector<int> joints) : s_(s), t_(t), joints_(std::move(joints)) {}

  void run(const std::string& step) {
    if (step == "find") return find();
    if (step == "which") return per_joint("which", [&](int j) { return which(j); });
    if (step == "direction") {
      // per_joint prints the step's heading; the pictures' place goes under it.
      return per_joint("direction", [&](int j) { return direction(j); }, true,
                       fmt::format("Pictures: docs/images/joints-{}.svg in armctl's sources (for another arm file: "
                                   "armctl calibrate --arm FILE --pictures OUT.svg)\n",
                                   model().family));
    }
    if (step == "zero") return released([&] { per_joint("zero", [&](int j) { return zero(j); }); });
    if (step == "limits") return released([&] { per_joint("limits", [&](int j) { return limits(j); }, true); });
    if (step == "gripper") return released([&] { gripper(); });
    if (step == "touch") return released([&] { touch(); });
    if (step == "fit") return fit();
  }

 private:
  const arm::ArmModel& model() const { return s_.model(); }
  const arm::JointModel& joint(int j) const { return model().joints[std::size_t(j)]; }

  template <typename F>
  void released(F f) {
    must(s_.release());
    t_.say("Torque off: the joints move by hand.\n");
    f();
    must(s_.hold());
  }

  // Each joint in turn; a step answers Next::redo to run again.
  template <typename F>
  void per_joint(const char* step, F f, bool chain_only = false, const std::string& intro = "") {
    t_.say(fmt::format("== {} ==\n{}", step, intro));
    for (int j : joints_) {
      if (chain_only && joint(j).role != arm::JointRole::chain) continue;
      while (f(j) == Next::redo) {
      }
    }
  }

  void find() {
    t_.say("== find: what answers ==\n");
    auto r = s_.find();
    if (!r) {
      t_.say(fmt::format("The arm does not answer: {}\n", r.error().message));
      return;
    }
    t_.say(r->text);
    while (!r->silent.empty()) {
      const std::string a = t_.ask(
          "Setting an ID reaches EVERY servo on the bus. Unplug all servos but one, then type the ID of the place it "
          "sits in (or Enter to go on):");
      if (a.empty()) return;
      char* end = nullptr;
      const long id = std::strtol(a.c_str(), &end, 10);
      if (end != a.c_str() + a.size() || id < 1 || id > 253) {
        t_.say(fmt::format("'{}': allowed an ID 1..253, Enter or q\n", a));
        continue;
      }
      if (Status st = s_.set_servo_id(int(id)); !st) {
        t_.say(st.error().message + "\n");
        continue;
      }
      t_.ask(fmt::format("Servo now answers ID {}. Plug the others back in, then press Enter:", id));
      r = s_.find();
      if (!r) return t_.say(r.error().message + "\n");
      t_.say(r->text);
    }
  }

  Next which(int j) {
    t_.say(fmt::format("Moving {} a little and back...\n", joint(j).name));
    if (Status st = s_.wiggle(j); !st) {
      t_.say(st.error().message + "\n");
      return enter(t_, "Go on?") == Next::redo ? Next::redo : Next::skip;
    }
    for (;;) {
      const std::string a = t_.ask(fmt::format("Which joint moved? (1..{} or a name; Enter: {}; r redo, s skip, q quit)",
                                               model().joint_count(), joint(j).name));
      if (a == "r") return Next::redo;
      if (a == "s") return Next::skip;
      auto moved = a.empty() ? Result<int>(j) : s_.joint_named(a);
      if (!moved) {
        t_.say(moved.error().message + "\n");
        continue;
      }
      if (Status st = s_.answer_which(j, *moved); !st) t_.say("Mix-up: " + st.error().message + "\n");
      return Next::done;
    }
  }

  Next direction(int j) {
    t_.say(fmt::format("Moving {} a little in its positive direction...\n", joint(j).name));
    if (Status st = s_.nudge(j); !st) {
      t_.say(st.error().message + "\n");
      return enter(t_, "Go on?") == Next::redo ? Next::redo : Next::skip;
    }
    Next next = Next::done;
    auto a = yes_no(t_, fmt::format("Did {} go the way panel {} of the pictures shows?", joint(j).name, j + 1), next);
    if (!a) return next;
    must(s_.answer_direction(j, *a));
    return Next::done;
  }

  Next zero(int j) {
    const double mark = calibration::mark_of(joint(j));
    Next n = enter(t_, fmt::format("Move {} by hand to its mark ({}), then", joint(j).name, value_text(joint(j), mark)));
    if (n != Next::done) return n;
    auto z = s_.zero_here(j, mark);
    if (!z) {
      t_.say(z.error().message + "\n");
      return Next::redo;
    }
    t_.say(z->kind == calibration::ZeroStep::Kind::servo_offset
               ? fmt::format("  {}: servo offset {} units (written to the servo when confirmed)\n", joint(j).name, z->servo_offset)
               : fmt::format("  {}: zero moves by {}\n", joint(j).name, value_text(joint(j), z->shift)));
    return Next::done;
  }

  Next limits(int j) {
    Next n = enter(t_, fmt::format("Move {} by hand to one end of its travel, then", joint(j).name));
    if (n != Next::done) return n;
    const double a = must(s_.read_joint(j));
    n = enter(t_, fmt::format("Now to its other end, then"));
    if (n != Next::done) return n;
    const double b = must(s_.read_joint(j));
    auto r = s_.limits(j, a, b);
    if (!r) {
      t_.say(r.error().message + "\n");
      return Next::redo;
    }
    t_.say(fmt::format("  {}: limits {} .. {}\n", joint(j).name, value_text(joint(j), r->lower), value_text(joint(j), r->upper)));
    return Next::done;
  }

  void gripper() {
    t_.say("== gripper ==\n");
    if (!model().gripper) return t_.say("This arm has no gripper.\n");
    const int g = model().gripper->joint;
    for (;;) {
      if (Next n = enter(t_, "Open the gripper by hand, then"); n == Next::skip) return;
      else if (n == Next::redo) continue;
      const double open = must(s_.read_joint(g));
      if (Next n = enter(t_, "Close it by hand, then"); n == Next::skip) return;
      else if (n == Next::redo) continue;
      auto r = s_.gripper(open, must(s_.read_joint(g)));
      if (!r) {
        t_.say(r.error().message + "\n");
        continue;
      }
      return t_.say(fmt::format("  gripper: open {}, closed {}\n", value_text(joint(g), r->open), value_text(joint(g), r->closed)));
    }
  }

  void touch() {
    t_.say("== touch: put the tool point on known points ==\n");
    std::vector<calibration::NamedPoint> marks;
    if (auto sheet = calibration::sheet_points(model(), calibration::default_placement(model()))) marks = *sheet;
    std::size_t next = 0;
    for (;;) {
      const std::string hint = next < marks.size()
                                   ? fmt::format("Tool on sheet mark {} ({:.1f} {:.1f} {:.1f} mm), Enter", marks[next].name,
                                                 marks[next].position.x() * 1000, marks[next].position.y() * 1000,
                                                 marks[next].position.z() * 1000)
                                   : std::string("Tool on a point you measured: type NAME X Y Z (mm)");
      const std::string a = t_.ask(hint + "; d done, s skip this mark, q quit:");
      if (a == "d") break;
      if (a == "s") {
        ++next;
        continue;
      }
      std::optional<calibration::NamedPoint> point;
      if (a.empty() && next < marks.size()) {
        point = marks[next];
      } else if (!a.empty()) {
        char name[64] = {};
        double x = 0, y = 0, z = 0;
        char extra = 0;
        if (std::sscanf(a.c_str(), "%63s %lf %lf %lf %c", name, &x, &y, &z, &extra) != 4) {
          t_.say(fmt::format("'{}': allowed Enter (on the mark), NAME X Y Z in mm, d, s or q\n", a));
          continue;
        }
        auto p = calibration::user_point(model(), name, Eigen::Vector3d(x, y, z) / 1000);
        if (!p) {
          t_.say(p.error().message + "\n");
          continue;
        }
        point = *p;
      } else {
        t_.say("Type NAME X Y Z (mm), d or q\n");
        continue;
      }
      auto touched = s_.touch(*point);
      if (!touched) {
        t_.say(touched.error().message + "\n");
        continue;
      }
      if (a.empty()) ++next;
      t_.say(fmt::format("  {} touched ({} points)\n", point->name, s_.touched().size()));
    }
    if (auto v = s_.verify()) t_.say("Residuals: " + calibration::to_text(*v) + "\n");
  }

  void fit() {
    t_.say("== fit: zeros and link lengths from the touched points ==\n");
    if (s_.touched().size() < calibration::kMinFitPoints)
      return t_.say(fmt::format("The fit needs at least {} touched points ({} so far): run the touch step.\n",
                                calibration::kMinFitPoints, s_.touched().size()));
    auto f = s_.fit();
    if (!f) return t_.say("Fit refused: " + f.error().message + "\n");
    t_.say(fmt::format("Residuals before {}\n       after  {}\n", calibration::to_text(f->before), calibration::to_text(f->after)));
  }

  calibration::CalibrationSession& s_;
  Terminal& t_;
  std::vector<int> joints_;
};

// The pictures the direction and zero steps refer to, for this arm file (docs/calibration.md
// "Pictures"); no device is opened.
void write_pictures(const CalibrateArgs& a) {
  const arm::ArmModel model = must(session::load_arm(a.arm));
  const std::string svg = must(calibration::joint_pictures_svg(model));
  must(write_file_atomically(a.pictures, std::span(reinterpret_cast<const std::uint8_t*>(svg.data()), svg.size())));
  fmt::print("{}: {} joints of {} at their marks and moved positive\n", a.pictures, model.joint_count(), model.name);
}

void run_calibrate(const CalibrateArgs& a) {
  if (!a.pictures.empty()) {
    if (!a.device.empty() || a.step != "all")
      throw ArmctlError(ErrorKind::invalid_argument,
                        "--pictures opens no device and runs no step: give it alone with --arm");
    return write_pictures(a);
  }
  if (a.step != "all" && std::find(kSteps.begin(), kSteps.end(), a.step) == kSteps.end())
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("step '{}': allowed all, find, which, direction, zero, limits, gripper, touch, fit", a.step));
  if (a.zero_in != "servo" && a.zero_in != "file")
    throw ArmctlError(ErrorKind::invalid_argument, fmt::format("--zero-in '{}': allowed servo or file", a.zero_in));
  // Through the arm session, like every command; a Robot Commands board's client is what the
  // wizard reaches its servos' IDs and offsets with.
  auto opened = must(session::open_arm_session(a.arm, a.device));
  arm::Arm* arm = opened->arm.get();
  const arm::ArmModel& model = arm->model();
  std::unique_ptr<calibration::RcServoBus> servos;
  if (opened->board) servos = std::make_unique<calibration::RcServoBus>(*opened->board);
  calibration::SessionOptions options;
  options.servo_offsets = a.zero_in == "servo";
  calibration::CalibrationSession s(*arm, servos.get(), options);
  std::vector<int> joints;
  if (a.joint.empty())
    for (int j = 0; j < model.joint_count(); ++j) joints.push_back(j);
  else
    joints.push_back(must(s.joint_named(a.joint)));

  Interrupted interrupted;
  StopOnSignals on_signals(interrupted);
  StdinLines input(interrupted.flag);
  Terminal t(input, interrupted);
  Wizard wizard(s, t, joints);
  t.say(fmt::format("Calibrating {} ({}), arm file {}\nNothing is written until you confirm at the end.\n", model.name,
                    arm->device().description(), model.file.string()));
  try {
    if (a.step == "all")
      for (const std::string& step : kSteps) wizard.run(step);
    else
      wizard.run(a.step);
    const std::string changes = s.describe();
    t.say("== changes ==\n" + changes);
    if (changes == "nothing to write\n") return;
    for (;;) {
      const std::string answer =
          t.ask(fmt::format("Write these to {} (the old file kept as {})? [y/n]", model.file.string(),
                            calibration::previous_file(model.file).string()));
      if (answer == "n" || answer == "no") return t.say("Not written.\n");
      if (answer == "y" || answer == "yes") break;
      t.say(fmt::format("'{}': allowed y, n or q\n", answer));
    }
    must(s.confirm());
    t.say(fmt::format("Written: {} (previous: {})\n", model.file.string(), calibration::previous_file(model.file).string()));
  } catch (const Quit& q) {
    (void)arm->set_torque(true);
    t.say(fmt::format("\n{}: nothing written.\n", q.why));
    if (q.why != "quit") throw ArmctlError(ErrorKind::invalid_argument, q.why + "; nothing written");
  } catch (...) {
    (void)arm->set_torque(true);
    throw;
  }
}

}  // namespace

void add_calibrate_command(CLI::App& app) {
  auto args = std::make_shared<CalibrateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate", "The guided calibration: find the servos, which joint is which, directions, zeros, limits, gripper, "
                   "touched points and the fit; written to the arm file only when confirmed (docs/calibration.md)");
  add_arm_options(cmd, args->arm, args->device);
  cmd->add_option("--joint", args->joint, "Only this joint (its name or number 1..N)");
  cmd->add_option("--zero-in", args->zero_in,
                  "servo (default): an xArm joint's zero goes to the servo's own offset when it fits -125..125 "
                  "units, else to the arm file; file: every zero goes to the arm file");
  cmd->add_option("--pictures", args->pictures,
                  "Write the pictures of each joint's mark and positive direction (SVG) to this file and stop; no "
                  "device is opened");
  cmd->add_option("step", args->step, "all (default) | find | which | direction | zero | limits | gripper | touch | fit");
  cmd->callback([args] { run_calibrate(*args); });
}

}  // namespace armctl::cli
