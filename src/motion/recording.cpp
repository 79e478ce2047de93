#include "motion/recording.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace armctl::motion {

std::vector<RecordingSample> smooth(const std::vector<RecordingSample>& samples, std::size_t half_window) {
  std::vector<RecordingSample> out = samples;
  if (samples.size() < 3 || half_window == 0) return out;
  for (std::size_t i = 1; i + 1 < samples.size(); ++i) {
    // A window symmetric around i, narrowed at the ends so that it stays centred (no lag).
    const std::size_t h = std::min({half_window, i, samples.size() - 1 - i});
    for (std::size_t j = 0; j < out[i].positions.size(); ++j) {
      double sum = 0;
      for (std::size_t k = i - h; k <= i + h; ++k) sum += samples[k].positions[j];
      out[i].positions[j] = sum / double(2 * h + 1);
    }
  }
  return out;
}

std::vector<std::size_t> keep_samples(const std::vector<RecordingSample>& samples,
                                      const std::vector<double>& tolerance) {
  if (samples.empty()) return {};
  if (samples.size() == 1) return {0};
  std::vector<bool> keep(samples.size(), false);
  keep.front() = keep.back() = true;
  // An explicit stack: recordings of 200,000 samples must not recurse that deep.
  std::vector<std::pair<std::size_t, std::size_t>> todo{{0, samples.size() - 1}};
  while (!todo.empty()) {
    const auto [a, b] = todo.back();
    todo.pop_back();
    if (b <= a + 1) continue;
    const double ta = samples[a].time, tb = samples[b].time;
    double worst = 1;  // in tolerances: above 1 the sample must be kept
    std::size_t worst_i = 0;
    for (std::size_t i = a + 1; i < b; ++i) {
      const double f = (samples[i].time - ta) / (tb - ta);
      for (std::size_t j = 0; j < samples[i].positions.size() && j < tolerance.size(); ++j) {
        const double line = samples[a].positions[j] + f * (samples[b].positions[j] - samples[a].positions[j]);
        const double e = std::abs(samples[i].positions[j] - line) / tolerance[j];
        if (e > worst) {
          worst = e;
          worst_i = i;
        }
      }
    }
    if (worst_i != 0) {
      keep[worst_i] = true;
      todo.push_back({a, worst_i});
      todo.push_back({worst_i, b});
    }
  }
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < keep.size(); ++i)
    if (keep[i]) out.push_back(i);
  return out;
}

}  // namespace armctl::motion
