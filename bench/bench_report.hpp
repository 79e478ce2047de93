// What every benchmark shares: the thread's CPU time (the machine that runs them is shared,
// and time spent preempted is not the code's) and the one line per figure that `make bench`
// prints: BENCH <name> <value> <unit> limit <limit> ratio <value / limit>.
#pragma once

#include <cstdio>
#include <ctime>
#include <string>

namespace armctl::bench {

// This thread's CPU time, ns.
inline double thread_cpu_ns() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e9 + double(t.tv_nsec);
}

inline void print(const std::string& name, double value, const char* unit, double limit) {
  std::printf("BENCH %s %.3f %s limit %.3f ratio %.3f\n", name.c_str(), value, unit, limit, value / limit);
  std::fflush(stdout);
}

}  // namespace armctl::bench
