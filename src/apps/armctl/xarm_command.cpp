// `armctl xarm`: drive an xArm (or our arm controller) over Robot Commands through the SDK.
// Thin: parse and validate arguments, call robot_commands::Client, print text or JSON.
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "apps/armctl/commands.hpp"
#include "apps/armctl/json_output.hpp"
#include "apps/armctl/number_options.hpp"
#include "apps/armctl/xarm_args.hpp"
#include "apps/armctl/serve_support.hpp"
#include "session/xarm_session.hpp"
#include "devices/robot_commands/arrival.hpp"
#include "files/action_group_file.hpp"
#include "protocol/robot_commands/units.hpp"

namespace armctl::cli {
namespace {

using robot_commands::Client;
using robot_commands::GroupEvent;

struct XarmCli {
  std::string device;
  bool json = false;
  int servo_count = 6;
  int timeout_ms = 0;  // 0 = the link's default

  // per-subcommand arguments
  std::vector<std::string> targets;
  int time_ms = 1000;
  bool wait = false;
  int tolerance = 10;
  int wait_timeout_ms = 1000;
  std::vector<std::string> servos;
  std::string servo;
  std::string offset;
  std::string mode;
  std::string speed = "0";
  bool speed_given = false;
  std::string file;
  std::string group;
  int times = 1;
  std::string percent;
  int interval_ms = 0;  // 0 = the link's poll interval
  int max_missed = 5;
  robot_commands::BusServoInfoWrite info;
};


template <typename T>
T check(Result<T> r) {
  return std::move(r).value();  // throws ArmctlError with the SDK's message
}

void print_json(const nlohmann::json& j) { print_json_line(j); }

nlohmann::json positions_json(const std::vector<robot_commands::ServoPosition>& ps) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& p : ps) {
    a.push_back({{"servo", p.servo},
                 {"position", p.position},
                 {"degrees", rc::position_to_degrees(p.position)}});
  }
  return a;
}

void print_positions(const XarmCli& o, const std::vector<robot_commands::ServoPosition>& ps) {
  if (o.json) return print_json({{"positions", positions_json(ps)}});
  for (const auto& p : ps) {
    fmt::print("servo {}: {:4} ({:+.1f} deg)\n", p.servo, p.position,
               rc::position_to_degrees(p.position));
  }
}

nlohmann::json event_json(const GroupEvent& e) {
  nlohmann::json j{{"event", robot_commands::to_string(e.kind)}, {"variant", e.variant}};
  if (e.group) j["group"] = *e.group;
  if (e.count) j["count"] = *e.count;
  return j;
}

void print_event(const XarmCli& o, const GroupEvent& e) {
  if (o.json) print_json(event_json(e));
  else fmt::print("{}\n", robot_commands::describe(e));
  std::fflush(stdout);
}

// Prints every event the board sent; how many.
std::size_t print_events(const XarmCli& o, Client& c) {
  std::size_t n = 0;
  for (; auto e = c.next_event(); ++n) print_event(o, *e);
  return n;
}

void done(const XarmCli& o, const std::string& text) {
  if (o.json) print_json({{"ok", true}, {"done", text}});
  else fmt::print("{}\n", text);
}

std::unique_ptr<session::XarmSession> open(const XarmCli& o) {
  return check(session::open_xarm_session(o.device, o.servo_count, o.timeout_ms));
}

void run_move(const XarmCli& o) {
  std::vector<robot_commands::ServoTarget> targets;
  for (const auto& t : o.targets) targets.push_back(xarm_args::parse_target(t, o.servo_count));
  auto s = open(o);
  check(s->client->move(targets, static_cast<std::uint16_t>(o.time_ms)));
  if (!o.wait) return done(o, fmt::format("moving {} servos over {} ms", targets.size(), o.time_ms));
  auto& c = *s->client;
  // Closed loop: read the servos back until they are there. The board may take longer than
  // --time (the xArm stretches a move to its speed limit) or not move at all (the arm
  // controller refuses a move for a joint that does not answer).
  const TimePoint sent = c.clock().now();
  robot_commands::ArrivalOptions arrival;
  arrival.tolerance = o.tolerance;
  arrival.not_before = sent + std::chrono::milliseconds(o.time_ms);
  const auto report = check(robot_commands::wait_until_arrived(
      c, targets, arrival.not_before + std::chrono::milliseconds(o.wait_timeout_ms), arrival));
  std::vector<robot_commands::ServoPosition> positions;
  for (const auto& a : report.servos) positions.push_back({a.servo, a.position});
  print_positions(o, positions);
  print_events(o, c);
  const auto missed = report.missed();
  if (missed.empty()) return;
  std::string names;
  for (const auto& m : missed) {
    names += fmt::format("{}servo {} at {} (target {})", names.empty() ? "" : ", ", m.servo,
                         m.position, *m.target);
  }
  throw ArmctlError(ErrorKind::device,
                    fmt::format("{} of {} servos did not arrive within {} ms of the move's {} ms "
                                "(tolerance {}): {}",
                                missed.size(), report.servos.size(), o.wait_timeout_ms, o.time_ms,
                                o.tolerance, names));
}

void run_positions(const XarmCli& o) {
  const auto ids = xarm_args::parse_servos(o.servos, o.servo_count);
  auto s = open(o);
  print_positions(o, check(s->client->read_positions(ids)));
}

void run_off(const XarmCli& o) {
  const auto ids = xarm_args::parse_servos(o.servos, o.servo_count);
  auto s = open(o);
  check(s->client->servos_off(ids));
  done(o, fmt::format("torque off for {} servos", ids.size()));
}

void run_battery(const XarmCli& o) {
  auto s = open(o);
  const auto mv = check(s->client->battery_millivolts());
  if (o.json) return print_json({{"millivolts", mv}});
  fmt::print("battery: {} mV ({:.2f} V)\n", mv, mv / 1000.0);
}

void run_offset_read(const XarmCli& o) {
  const auto ids = xarm_args::parse_servos(o.servos, o.servo_count);
  auto s = open(o);
  const auto offsets = check(s->client->read_offsets(ids));
  if (o.json) {
    nlohmann::json a = nlohmann::json::array();
    for (const auto& x : offsets) a.push_back({{"servo", x.servo}, {"offset", x.offset}});
    return print_json({{"offsets", a}});
  }
  for (const auto& x : offsets) fmt::print("servo {}: offset {:+}\n", x.servo, x.offset);
}

void run_offset_adjust(const XarmCli& o) {
  const auto servo = xarm_args::parse_servo(o.servo, o.servo_count);
  const auto offset = xarm_args::parse_int(o.offset, rc::kOffsetMin, rc::kOffsetMax, "offset");
  auto s = open(o);
  check(s->client->adjust_offset(servo, static_cast<int>(offset)));
  done(o, fmt::format("servo {} offset set to {:+} (until power-off; `offset save` keeps it)",
                      servo, offset));
}

void run_offset_save(const XarmCli& o) {
  const auto ids = xarm_args::parse_servos(o.servos, o.servo_count);
  auto s = open(o);
  check(s->check(s->client->save_offsets(ids)));
  // ServoOffsetWrite has no reply: only the embedded board can say whether it stored them.
  if (check(s->confirm_accepted("ServoOffsetWrite"))) return done(o, fmt::format("offsets saved for {} servos", ids.size()));
  done(o, fmt::format("offset save sent for {} servos (not confirmed: Robot Commands has no reply to it; a board "
                      "that cannot store them says so only in its own log)",
                      ids.size()));
}

void run_mode(const XarmCli& o) {
  const auto servo = xarm_args::parse_servo(o.servo, o.servo_count);
  rc::ServoMode mode;
  if (o.mode == "servo") mode = rc::ServoMode::servo;
  else if (o.mode == "motor") mode = rc::ServoMode::motor;
  else throw ArmctlError(ErrorKind::invalid_argument,
                         fmt::format("mode \"{}\" is not allowed (servo or motor)", o.mode));
  if (mode == rc::ServoMode::motor && !o.speed_given)
    throw ArmctlError(ErrorKind::invalid_argument,
                      "mode motor needs --speed -1000..1000 (negative = reverse; 0 holds the motor still)");
  const auto speed = xarm_args::parse_int(o.speed, -1000, 1000, "--speed");
  auto s = open(o);
  check(s->client->set_mode(servo, mode, static_cast<std::int16_t>(speed)));
  done(o, fmt::format("servo {} in {} mode", servo, o.mode));
}

void run_info_read(const XarmCli& o) {
  auto s = open(o);
  const auto i = check(s->client->read_bus_servo_info());
  nlohmann::json j{{"id", i.id},
                   {"position_min", i.position_min},
                   {"position_max", i.position_max},
                   {"millivolts_min", i.millivolts_min},
                   {"millivolts_max", i.millivolts_max},
                   {"temp_max", i.temp_max},
                   {"led_status", i.led_status},
                   {"led_warning", i.led_warning},
                   {"offset", i.offset},
                   {"position", i.position},
                   {"temp", i.temp},
                   {"millivolts", i.millivolts}};
  if (o.json) return print_json(j);
  for (auto it = j.begin(); it != j.end(); ++it) fmt::print("{}: {}\n", it.key(), it->dump());
}

void run_info_write(const XarmCli& o) {
  auto s = open(o);
  check(s->check(s->client->write_bus_servo_info(o.info)));
  if (check(s->confirm_accepted("BusServoInfoWrite"))) return done(o, fmt::format("bus servo info written (ID {})", o.info.servo));
  done(o, fmt::format("bus servo info sent (ID {}; not confirmed: Robot Commands has no reply to it)", o.info.servo));
}

void run_group_download(const XarmCli& o) {
  const auto group = xarm_args::parse_group(o.group, false);
  const auto file = check(files::read_action_group_file(o.file));
  auto s = open(o);
  check(s->check(s->client->download_group(group, file.actions)));
  done(o, fmt::format("group {}: {} actions downloaded", group, file.actions.size()));
}

// `group run --wait`: prints notifications until the run finishes or is stopped (or Ctrl-C).
// Needed with the embedded board, which plays only while this command runs.
void wait_for_group_end(const XarmCli& o, Client& c, std::uint8_t group) {
  Interrupted interrupted;
  const StopOnSignals stop_on_signals(interrupted);
  // As long as a reply may take (500 ms on serial, 1.5 s on slow HID boards).
  const Duration start_wait = c.options().reply_timeout;
  const TimePoint start_deadline = c.clock().now() + start_wait;
  bool started = false;
  while (!interrupted) {
    auto e = c.wait_event(c.clock().now() + std::chrono::milliseconds(100));
    if (!e) {
      if (e.error().kind != ErrorKind::timeout) throw ArmctlError(e.error());
      if (!started && c.clock().now() >= start_deadline) {
        throw ArmctlError(ErrorKind::timeout,
                          fmt::format("no 'started' notification for group {} within {} ms (is "
                                      "group {} empty on this board?)",
                                      group,
                                      std::chrono::duration_cast<std::chrono::milliseconds>(
                                          start_wait)
                                          .count(),
                                      group));
      }
      continue;
    }
    print_event(o, *e);
    if (e->kind == robot_commands::GroupEventKind::started) started = true;
    if (e->kind == robot_commands::GroupEventKind::finished ||
        e->kind == robot_commands::GroupEventKind::stopped)
      break;
  }
}

void run_group_run(const XarmCli& o) {
  const auto group = xarm_args::parse_group(o.group, false);
  auto s = open(o);
  check(s->client->run_group(group, static_cast<std::uint16_t>(o.times)));
  done(o, o.times == 0 ? fmt::format("group {} running until stopped", group)
                       : fmt::format("group {} running {} times", group, o.times));
  if (o.wait) return wait_for_group_end(o, *s->client, group);
  check(s->client->pump_events(s->client->clock().now() + std::chrono::milliseconds(200)));
  if (s->client->pending_events() == 0 && !o.json) {
    fmt::print(stderr, "warning: no 'started' notification within 200 ms (is group {} empty on "
                       "this board?)\n", group);
  }
  print_events(o, *s->client);
}

void run_group_stop(const XarmCli& o) {
  auto s = open(o);
  check(s->client->stop_group());
  check(s->client->pump_events(s->client->clock().now() + std::chrono::milliseconds(100)));
  // A running group's end is the board's own "group stopped" event: said once, not twice.
  if (print_events(o, *s->client) == 0 || o.json)
    done(o, "group stop sent");
}

void run_group_erase(const XarmCli& o) {
  const auto group = xarm_args::parse_group(o.group, true);
  auto s = open(o);
  check(s->check(s->client->erase_group(group)));
  done(o, group == 255 ? std::string("all groups erased") : fmt::format("group {} erased", group));
}

void run_group_speed(const XarmCli& o) {
  const auto group = xarm_args::parse_group(o.group, true);
  const auto pct = xarm_args::parse_int(o.percent, rc::kSpeedPercentMin, rc::kSpeedPercentMax,
                                        "speed percentage");
  auto s = open(o);
  check(s->client->set_group_speed(group, static_cast<std::uint16_t>(pct)));
  done(o, fmt::format("group {} speed {} %", o.group, pct));
}

// Polls positions at the link's poll interval (or --interval). A real board misses a reply
// now and then: a missed poll is counted and shown, and watch stops only after
// --max-missed polls in a row have failed. A link that fails (unplugged) stops it at once.
void run_watch(const XarmCli& o) {
  auto s = open(o);
  auto& c = *s->client;
  const Duration interval = o.interval_ms > 0 ? Duration{std::chrono::milliseconds(o.interval_ms)}
                                              : c.options().poll_interval;
  Interrupted interrupted;
  const StopOnSignals stop_on_signals(interrupted);
  int missed_in_row = 0;
  int missed_total = 0;
  while (!interrupted) {
    const std::size_t retries_before = c.stats().read_retries;
    auto ps = c.read_all_positions();
    // Replies the client's read retries rode out are missed replies too: show them.
    const auto resent = static_cast<int>(c.stats().read_retries - retries_before);
    if (ps && resent > 0) {
      missed_total += resent;
      if (o.json) {
        print_json({{"missed", "no reply in time; sent again and answered"},
                    {"resent", resent},
                    {"missed_in_row", 0},
                    {"missed_total", missed_total}});
      } else {
        fmt::print("missed {} repl{}; sent again and answered ({} in all)\n", resent,
                   resent == 1 ? "y" : "ies", missed_total);
      }
    }
    if (!ps) {
      missed_total += resent;
      const auto kind = ps.error().kind;
      if (kind != ErrorKind::timeout && kind != ErrorKind::protocol) throw ArmctlError(ps.error());
      ++missed_in_row;
      ++missed_total;
      if (o.json) {
        print_json({{"missed", ps.error().message},
                    {"missed_in_row", missed_in_row},
                    {"missed_total", missed_total}});
      } else {
        fmt::print("missed ({} in a row, {} in all): {}\n", missed_in_row, missed_total,
                   ps.error().message);
      }
      std::fflush(stdout);
      if (missed_in_row >= o.max_missed) {
        throw ArmctlError(kind, fmt::format("watch: {} polls in a row got no usable reply "
                                            "(--max-missed {}); last: {}",
                                            missed_in_row, o.max_missed, ps.error().message));
      }
    } else {
      missed_in_row = 0;
      if (o.json) {
        print_json({{"positions", positions_json(*ps)}});
      } else {
        std::string line;
        for (const auto& p : *ps) line += fmt::format("{}={:<5}", p.servo, p.position);
        fmt::print("{}\n", line);
      }
    }
    print_events(o, c);
    std::fflush(stdout);
    check(c.pump_events(c.clock().now() + interval));
    print_events(o, c);
  }
}

}  // namespace

void add_xarm_command(CLI::App& app) {
  auto o = std::make_shared<XarmCli>();
  auto* x = app.add_subcommand("xarm", "Drive an xArm board (or the arm controller) over Robot "
                                       "Commands; without --device an embedded emulated xArm");
  x->footer(
      "Without --device (or with --device sim) each command talks to an emulated xArm embedded\n"
      "in this process. Like a real board it keeps action groups, saved offsets and servo limits\n"
      "between commands, in $ARMCTL_STATE_DIR/xarm-emulator, else\n"
      "$XDG_STATE_HOME/armctl/xarm-emulator, else ~/.local/state/armctl/xarm-emulator. Servo\n"
      "positions are not kept: every command starts with all servos at centre (500), and a group\n"
      "plays only while its command runs (use `group run N --wait`). For one long-lived board:\n"
      "`armctl sim xarm --link /tmp/xarm` and --device /tmp/xarm.");
  x->require_subcommand(1);
  x->fallthrough();  // --device/--json may also follow the subcommand
  x->add_option("--device", o->device,
                "sim (embedded emulated xArm, default) | hid | hid:SERIAL | hid:/dev/hidrawN | "
                "serial:/dev/ttyUSB0[?baud=115200] | /dev/PATH");
  x->add_flag("--json", o->json, "Machine-readable output (one JSON object per line)");
  x->add_option("--servos", o->servo_count, "Servos on the board (6 = xArm, 7 = SCARA controller)")
      ->check(whole_number_in(1, rc::kMaxServosPerFrame));
  x->add_option("--timeout", o->timeout_ms,
                "Reply timeout in ms (default 1500 on HID, 500 otherwise; docs/usb-hid.md)")
      ->check(whole_number_in(1, 60000));

  auto* move = x->add_subcommand("move", "Move servos: 1=500 2=30deg 3=keep");
  move->add_option("targets", o->targets, "SERVO=POSITION (0..1000, -120deg..120deg, keep)")
      ->required();
  move->add_option("--time", o->time_ms, "Move time in ms")->check(whole_number_in(0, rc::kMoveTimeMaxMs));
  move->add_flag("--wait", o->wait,
                 "Read the servos back until they arrive, print their positions; exit non-zero "
                 "naming every servo that did not arrive");
  move->add_option("--tolerance", o->tolerance,
                   "With --wait: how close counts as arrived, in servo units (default 10)")
      ->check(whole_number_in(0, rc::kPositionMax));
  move->add_option("--wait-timeout", o->wait_timeout_ms,
                   "With --wait: how long after --time to wait for arrival, in ms (default 1000)")
      ->check(whole_number_in(0, 60000));
  move->callback([o] { run_move(*o); });

  auto* positions = x->add_subcommand("positions", "Read servo positions");
  positions->add_option("servos", o->servos, "Servo IDs (default: all)");
  positions->callback([o] { run_positions(*o); });

  auto* off = x->add_subcommand("off", "Remove torque (the next move restores it)");
  off->add_option("servos", o->servos, "Servo IDs (default: all)");
  off->callback([o] { run_off(*o); });

  x->add_subcommand("battery", "Battery voltage")->callback([o] { run_battery(*o); });

  auto* offset = x->add_subcommand("offset", "Servo offsets (-125..125)");
  offset->require_subcommand(1);
  auto* oread = offset->add_subcommand("read", "Read offsets");
  oread->add_option("servos", o->servos, "Servo IDs (default: all)");
  oread->callback([o] { run_offset_read(*o); });
  auto* oadj = offset->add_subcommand("adjust", "Set an offset now (lost at power-off)");
  oadj->add_option("servo", o->servo)->required();
  oadj->add_option("offset", o->offset, "-125..125")->required();
  oadj->callback([o] { run_offset_adjust(*o); });
  auto* osave = offset->add_subcommand("save", "Keep the current offsets across power-off");
  osave->add_option("servos", o->servos, "Servo IDs (default: all)");
  osave->callback([o] { run_offset_save(*o); });

  auto* mode = x->add_subcommand("mode", "Servo or motor mode (ServoSpeed)");
  mode->add_option("servo", o->servo)->required();
  mode->add_option("mode", o->mode, "servo | motor")->required();
  mode->add_option("--speed", o->speed, "Motor-mode speed -1000..1000 (negative = reverse); required for motor")
      ->each([o](const std::string&) { o->speed_given = true; });
  mode->callback([o] { run_mode(*o); });

  auto* info = x->add_subcommand("info", "Bus-servo info (one servo on the bus)");
  info->require_subcommand(1);
  info->add_subcommand("read", "Read limits and readings")->callback([o] { run_info_read(*o); });
  auto* iw = info->add_subcommand("write", "Write ID, limits and LED settings");
  // The SDK checks the ID against the board's servos (--servos) and min <= max; these checks
  // keep a value from wrapping in its u8/u16 field first.
  iw->add_option("--id", o->info.servo, "Servo ID to give")
      ->required()
      ->check(whole_number_in(1, rc::kMaxServosPerFrame));
  iw->add_option("--position-min", o->info.position_min)->check(whole_number_in(rc::kPositionMin, rc::kPositionMax));
  iw->add_option("--position-max", o->info.position_max)->check(whole_number_in(rc::kPositionMin, rc::kPositionMax));
  iw->add_option("--millivolts-min", o->info.millivolts_min)
      ->check(whole_number_in(rc::kMillivoltsMin, rc::kMillivoltsMax));
  iw->add_option("--millivolts-max", o->info.millivolts_max)
      ->check(whole_number_in(rc::kMillivoltsMin, rc::kMillivoltsMax));
  iw->add_option("--temp-max", o->info.temp_max, "Temperature limit in C")
      ->check(whole_number_in(rc::kTempMaxMin, rc::kTempMaxMax));
  iw->add_option("--led-status", o->info.led_status, "0 enable, 1 disable")->check(whole_number_in(0, 1));
  iw->add_option("--led-warning", o->info.led_warning, "bits: 1 overheat, 2 overvoltage, 4 overposition")
      ->check(whole_number_in(0, 7));
  iw->callback([o] { run_info_write(*o); });

  auto* group = x->add_subcommand("group", "Action groups");
  group->require_subcommand(1);
  auto* gd = group->add_subcommand("download", "Download a group file (docs/action-groups.md)");
  gd->add_option("file", o->file)->required();
  gd->add_option("--group", o->group, "Group number 0..254")->default_val("0");
  gd->callback([o] { run_group_download(*o); });
  auto* gr = group->add_subcommand("run", "Run a group");
  gr->add_option("group", o->group)->required();
  gr->add_option("--times", o->times, "0 = until stopped")->check(whole_number_in(0, 65535));
  gr->add_flag("--wait", o->wait,
               "Print notifications until the run finishes or is stopped (or Ctrl-C)");
  gr->callback([o] { run_group_run(*o); });
  group->add_subcommand("stop", "Stop the running group")->callback([o] { run_group_stop(*o); });
  auto* ge = group->add_subcommand("erase", "Erase a group (or all)");
  ge->add_option("group", o->group, "0..254 | all")->required();
  ge->callback([o] { run_group_erase(*o); });
  auto* gs = group->add_subcommand("speed", "Playback speed in % (100 = as recorded)");
  gs->add_option("group", o->group, "0..254 | all")->required();
  gs->add_option("percent", o->percent, "1..1000")->required();
  gs->callback([o] { run_group_speed(*o); });
  add_group_rob_commands(*group, {&o->device, &o->servo_count, &o->timeout_ms});

  auto* watch = x->add_subcommand("watch", "Live positions and notifications until Ctrl-C");
  watch->add_option("--interval", o->interval_ms,
                    "ms between reads (default 500 on HID, 200 otherwise; docs/usb-hid.md)")
      ->check(whole_number_in(10, 60000));
  watch->add_option("--max-missed", o->max_missed,
                    "Stop after this many polls in a row without a usable reply")
      ->check(whole_number_in(1, 1000));
  watch->callback([o] { run_watch(*o); });
}

}  // namespace armctl::cli
