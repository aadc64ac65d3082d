#pragma once
#include <string>
#include <vector>

#include "renderers/renderer.h"

namespace sdfbench {

struct FrameTimingSummary {
  std::string clock;  // "device" (GPU timestamps) or "wall"
  double median_ms = 0, min_ms = 0, max_ms = 0;
  double wall_median_ms = 0;
  double fps = 0;          // 1000 / median_ms
  double mrays_per_s = 0;  // rays of a frame / median time
};

// Median/min/max over timed frames, on GPU timestamps when every frame has them, else wall clock.
FrameTimingSummary summarize_frames(const std::vector<FrameResult>& frames);

double median(std::vector<double> values);

}  // namespace sdfbench
