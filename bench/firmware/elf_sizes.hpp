// Flash and static RAM of an AVR ELF (avr-size -A), and the BENCH line format, for the
// firmware benchmarks (joint controller and Mega controller).
#pragma once

#include <cstdio>
#include <string>

namespace armctl::bench {

inline void bench_line(const char* name, double value, const char* unit, double limit) {
  std::printf("BENCH %s %.0f %s limit %.0f ratio %.3f\n", name, value, unit, limit, value / limit);
}

struct Sizes {
  unsigned long text = 0, data = 0, bss = 0, noinit = 0;
  bool ok = false;
};

inline Sizes elf_sizes(const std::string& elf) {
  Sizes s;
  const std::string cmd = "avr-size -A '" + elf + "'";
  FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) return s;
  char name[64];
  unsigned long size = 0, addr = 0;
  char line[256];
  while (std::fgets(line, sizeof line, p) != nullptr) {
    if (std::sscanf(line, "%63s %lu %lu", name, &size, &addr) != 3) continue;
    const std::string n = name;
    if (n == ".text") s.text = size;
    if (n == ".data") s.data = size;
    if (n == ".bss") s.bss = size;
    if (n == ".noinit") s.noinit = size;
  }
  s.ok = pclose(p) == 0 && s.text > 0;
  return s;
}

}  // namespace armctl::bench
