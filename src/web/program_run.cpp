#include "web/program_run.hpp"

namespace armctl::web {

const char* to_string(ProgramState s) {
  switch (s) {
    case ProgramState::running: return "running";
    case ProgramState::paused: return "paused";
    default: return "idle";
  }
}

std::optional<ProgramView> ProgramRun::view() const {
  std::lock_guard lock(mutex_);
  return view_;
}

void ProgramRun::started() {
  std::lock_guard lock(mutex_);
  view_ = ProgramView{};
  view_->state = ProgramState::running;
}

void ProgramRun::at(std::size_t line, std::size_t column, double left_s) {
  std::lock_guard lock(mutex_);
  if (!view_) return;
  view_->line = line;
  view_->column = column;
  view_->left_s = left_s;
}

void ProgramRun::print(std::string text) {
  std::lock_guard lock(mutex_);
  if (!view_) return;
  view_->prints.push_back(std::move(text));
  if (view_->prints.size() > kMaxPrints) view_->prints.erase(view_->prints.begin());
}

void ProgramRun::paused(bool paused) {
  std::lock_guard lock(mutex_);
  if (view_ && view_->state != ProgramState::idle) view_->state = paused ? ProgramState::paused : ProgramState::running;
}

void ProgramRun::ended() {
  std::lock_guard lock(mutex_);
  if (!view_) return;
  view_->state = ProgramState::idle;
  view_->left_s = 0;
}

}  // namespace armctl::web
