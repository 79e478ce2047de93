// transport::ServeLoop, the wait every server in armctl loops on: ready descriptors, timeouts,
// and a stop that wakes it at once from another thread or a signal handler.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "transport/serve_loop.hpp"

namespace armctl::test {
namespace {

using namespace std::chrono_literals;
using transport::ServeLoop;

struct Pipe {
  int fds[2] = {-1, -1};
  Pipe() { EXPECT_EQ(::pipe(fds), 0); }
  Pipe(const Pipe&) = delete;
  Pipe& operator=(const Pipe&) = delete;
  ~Pipe() {
    ::close(fds[0]);
    ::close(fds[1]);
  }
};

TEST(ServeLoop, ReportsAReadyDescriptor) {
  ServeLoop loop;
  Pipe p;
  ASSERT_EQ(::write(p.fds[1], "x", 1), 1);
  pollfd fds[1] = {{p.fds[0], POLLIN, 0}};
  EXPECT_TRUE(loop.wait(fds, std::nullopt));  // no timeout: returns because the pipe is ready
  EXPECT_TRUE(fds[0].revents & POLLIN);
}

TEST(ServeLoop, ZeroTimeoutOnlyLooks) {
  ServeLoop loop;
  Pipe p;
  pollfd fds[1] = {{p.fds[0], POLLIN, 0}};
  EXPECT_TRUE(loop.wait(fds, Duration::zero()));
  EXPECT_EQ(fds[0].revents, 0);
}

TEST(ServeLoop, ATimeoutEndsTheWaitNoEarlier) {
  ServeLoop loop;
  Pipe p;
  pollfd fds[1] = {{p.fds[0], POLLIN, 0}};
  const SteadyClock clock;
  const TimePoint start = clock.now();
  EXPECT_TRUE(loop.wait(fds, 20ms));
  EXPECT_GE(clock.now() - start, 20ms);
  EXPECT_EQ(fds[0].revents, 0);
}

TEST(ServeLoop, AStopFromAnotherThreadWakesAWaitWithoutTimeout) {
  ServeLoop loop;
  Pipe p;  // never written: only the stop can end the wait
  std::thread stopper([&] { loop.request_stop(); });
  pollfd fds[1] = {{p.fds[0], POLLIN, 0}};
  EXPECT_FALSE(loop.wait(fds, std::nullopt));
  stopper.join();
  EXPECT_TRUE(loop.stop_requested());
  EXPECT_FALSE(loop.wait(fds, Duration::zero()));  // stays stopped
  loop.clear_stop();
  EXPECT_FALSE(loop.stop_requested());
  EXPECT_TRUE(loop.wait(fds, Duration::zero()));
}

ServeLoop* g_loop = nullptr;
extern "C" void stop_from_signal(int) { g_loop->request_stop(); }

TEST(ServeLoop, AStopFromASignalHandlerWakesTheWait) {
  ServeLoop loop;
  g_loop = &loop;
  struct sigaction action {}, old {};
  action.sa_handler = stop_from_signal;
  sigemptyset(&action.sa_mask);
  ASSERT_EQ(sigaction(SIGUSR1, &action, &old), 0);
  const pthread_t waiter = pthread_self();
  std::thread signaller([&] { pthread_kill(waiter, SIGUSR1); });
  Pipe p;
  pollfd fds[1] = {{p.fds[0], POLLIN, 0}};
  EXPECT_FALSE(loop.wait(fds, std::nullopt));
  signaller.join();
  sigaction(SIGUSR1, &old, nullptr);
  g_loop = nullptr;
}

TEST(ServeLoop, ManyDescriptors) {
  ServeLoop loop;
  std::vector<Pipe> pipes(12);
  ASSERT_EQ(::write(pipes[11].fds[1], "x", 1), 1);
  std::vector<pollfd> fds;
  for (auto& p : pipes) fds.push_back({p.fds[0], POLLIN, 0});
  EXPECT_TRUE(loop.wait(fds, std::nullopt));
  for (std::size_t i = 0; i < 11; ++i) EXPECT_EQ(fds[i].revents, 0) << i;
  EXPECT_TRUE(fds[11].revents & POLLIN);
}

}  // namespace
}  // namespace armctl::test
