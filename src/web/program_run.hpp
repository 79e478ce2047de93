// What the dashboard shows of the program that runs (or ran last): the line it is at, the
// time left, whether it runs or is paused, and what it printed. Written by the program
// job on the arm worker's thread, read by every request for the state. Thread-safe.
#pragma once

#include <cstddef>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace armctl::web {

enum class ProgramState { idle, running, paused };
const char* to_string(ProgramState s);

struct ProgramView {
  std::size_t line = 0, column = 0;
  double left_s = 0;
  ProgramState state = ProgramState::idle;
  std::vector<std::string> prints;
};

inline constexpr std::size_t kMaxPrints = 200;  // the latest kept

class ProgramRun {
 public:
  // nullopt until a program was started.
  std::optional<ProgramView> view() const;
  void started();
  void at(std::size_t line, std::size_t column, double left_s);
  void print(std::string text);
  void paused(bool paused);
  void ended();

 private:
  mutable std::mutex mutex_;
  std::optional<ProgramView> view_;
};

}  // namespace armctl::web
