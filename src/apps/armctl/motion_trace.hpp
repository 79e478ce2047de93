// --trace FILE of `armctl arm path` and `armctl program run`: where the tool was planned to
// be and where it was read back, as CSV, so that a run can be plotted or checked by a script
// (scripts/demo_picture.py draws the demo's picture from it). One row a line:
//
//   kind,line,t_s,planned_x_mm,planned_y_mm,planned_z_mm,measured_x_mm,measured_y_mm,measured_z_mm
//
//   plan  the plan, sampled every 20 ms of its nominal time; the measured columns are empty
//   read  one read-back during the motion: the plan at that instant and the tool measured
//
// `line` is the path or program line the motion piece starts at. t_s counts from the start
// of the first traced piece and adds up the pieces' run times (a program's WAITs between
// them are left out): nominal time for plan rows, the device's clock for read rows (the two
// agree at 100 % override on a host that kept up). Rows are written after each piece, so a
// run stopped part way keeps what ran.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>

#include "arm/arm.hpp"
#include "arm/motion_executor.hpp"

namespace CLI {
class Validator;  // <CLI/CLI.hpp>: heavy, and only the commands that add the option need it
}

namespace armctl::cli {

// The --trace option's check: a file name (an empty one is refused, not taken as "no trace").
CLI::Validator trace_file_check();

class MotionTrace {
 public:
  // Creates (or empties) `path` and writes the header: throws ArmctlError (io) naming the file
  // and why it cannot be written, so that a bad path is refused before anything moves.
  explicit MotionTrace(const std::string& path);
  ~MotionTrace();
  MotionTrace(const MotionTrace&) = delete;
  MotionTrace& operator=(const MotionTrace&) = delete;

  // One motion piece that ran: its plan sampled and every read-back, tool positions through
  // the arm's forward kinematics. Throws ArmctlError (io) if the file cannot take the rows.
  void add(const arm::Arm& arm, std::size_t line, const arm::PlannedMotion& motion, const arm::MotionReport& report);

  // Closes the file; throws ArmctlError (io) if the last rows could not be written.
  void finish();

 private:
  void check(int result);

  std::string path_;
  std::FILE* file_ = nullptr;
  double t0_ = 0;  // s: where the next piece starts on the trace's time axis
};

}  // namespace armctl::cli
