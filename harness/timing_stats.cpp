#include "harness/timing_stats.h"

#include <algorithm>

namespace sdfbench {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

FrameTimingSummary summarize_frames(const std::vector<FrameResult>& frames) {
  FrameTimingSummary s;
  if (frames.empty()) return s;
  const bool device = std::all_of(frames.begin(), frames.end(), [](const FrameResult& f) { return f.device_ms >= 0.0; });
  s.clock = device ? "device" : "wall";
  std::vector<double> ms, wall;
  for (const FrameResult& f : frames) {
    ms.push_back(device ? f.device_ms : f.wall_ms);
    wall.push_back(f.wall_ms);
  }
  s.median_ms = median(ms);
  s.min_ms = *std::min_element(ms.begin(), ms.end());
  s.max_ms = *std::max_element(ms.begin(), ms.end());
  s.wall_median_ms = median(wall);
  if (s.median_ms > 0.0) {
    s.fps = 1000.0 / s.median_ms;
    s.mrays_per_s = static_cast<double>(frames.back().rays) / (s.median_ms * 1e3);
  }
  return s;
}

}  // namespace sdfbench
