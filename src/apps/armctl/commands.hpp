// Each armctl subcommand lives in its own file and registers itself here. Subcommands stay
// thin: they parse and validate arguments, call the SDK or a device, and print.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace armctl::cli {

void add_bus_command(CLI::App& app);         // bus_command.cpp: joint bus master
void add_sim_command(CLI::App& app);         // sim_command.cpp: long-lived simulated arms
void add_sim_xarm_command(CLI::App& sim);    // sim_xarm_command.cpp: `sim xarm`, the xArm emulator
void add_xarm_command(CLI::App& app);        // xarm_command.cpp: Robot Commands SDK
void add_emulate_command(CLI::App& app);     // sim_xarm_command.cpp: deprecated name of sim xarm
void add_list_command(CLI::App& app);        // list_command.cpp: attached boards and ports
void add_controller_command(CLI::App& app);  // controller_command.cpp: the arm controller
void add_arm_command(CLI::App& app);         // arm_command.cpp: the Arm API in SI units
void add_stop_command(CLI::App& app);        // stop_command.cpp: stop any device now
void add_program_command(CLI::App& app);     // program_command.cpp: robot programs
void add_teach_command(CLI::App& app);       // teach_command.cpp: points and motions taught by hand
void add_jog_command(CLI::App& app);         // jog_command.cpp: the arm driven from the keyboard
void add_follow_command(CLI::App& app);      // follow_command.cpp: a follower arm copies a leader moved by hand
void add_replay_command(CLI::App& app);      // replay_command.cpp: recordings played back
void add_serve_command(CLI::App& app);       // serve_command.cpp: the web dashboard and its HTTP API
void add_calibrate_command(CLI::App& app);   // calibrate_command.cpp: the guided calibration wizard

// --arm and --device as the commands that open an arm through the Arm API take them (teach,
// serve, program; `armctl arm` says more about --device in its own help).
inline void add_arm_options(CLI::App* cmd, std::string& arm, std::string& device) {
  cmd->add_option("--arm", arm, "xarm | scara | an arm file (default xarm)");
  cmd->add_option("--device", device, "As for `armctl arm` (default: the embedded simulated arm)");
}

// Where `armctl xarm --device ...` options end up (they are parsed after the subcommand is set up).
struct XarmDeviceOptions {
  const std::string* device;
  const int* servo_count;
  const int* timeout_ms;
};
// group_rob_command.cpp: `xarm group import|export` (.rob files)
void add_group_rob_commands(CLI::App& group, const XarmDeviceOptions& device);

}  // namespace armctl::cli
