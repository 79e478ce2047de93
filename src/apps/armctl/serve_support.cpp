#include "apps/armctl/serve_support.hpp"

#include <system_error>

#include <fmt/core.h>

#include "core/error.hpp"

namespace armctl::cli {

namespace fs = std::filesystem;

PtySymlink::PtySymlink(const fs::path& link, const fs::path& target) {
  if (link.empty()) return;
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(link, ec))) fs::remove(link, ec);
  fs::create_symlink(target, link, ec);
  if (ec) {
    throw ArmctlError(ErrorKind::io, fmt::format("cannot create link {} -> {}: {}", link.string(),
                                                 target.string(), ec.message()));
  }
  link_ = link;
}

PtySymlink::~PtySymlink() {
  if (link_.empty()) return;
  std::error_code ec;
  fs::remove(link_, ec);
}

namespace {

void (*g_stop)(void*) = nullptr;
void* g_context = nullptr;
std::atomic<int> g_last_signal{0};  // lock-free: a signal handler may store it
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void on_stop_signal(int signal) {
  g_last_signal.store(signal);
  if (g_stop != nullptr) g_stop(g_context);
}

}  // namespace

int last_stop_signal() { return g_last_signal.load(); }

StopOnSignals::StopOnSignals(void (*stop)(void*), void* context) {
  g_stop = stop;
  g_context = context;
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &old_int_);
  sigaction(SIGTERM, &action, &old_term_);
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  sigaction(SIGPIPE, &ignore, &old_pipe_);
}

StopOnSignals::~StopOnSignals() {
  sigaction(SIGINT, &old_int_, nullptr);
  sigaction(SIGTERM, &old_term_, nullptr);
  sigaction(SIGPIPE, &old_pipe_, nullptr);
  g_stop = nullptr;
  g_context = nullptr;
}

}  // namespace armctl::cli
