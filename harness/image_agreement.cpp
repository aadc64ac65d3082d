#include "harness/image_agreement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>


#include "renderers/shading/gpu_types.h"
#include "util/error.h"

namespace sdfbench {
namespace {

bool is_instance(uint32_t id) { return id < shading::FLOOR_INSTANCE_VALUE; }

// Per-channel absolute differences of the RGB images (alpha is not compared): their mean and
// RMS over all channel values, and the pixels where a channel differs by more than `fail`. The
// same definitions as OpenImageIO's ImageBufAlgo::compare / idiff, which the tests check.
struct ColourDifference {
  double mean = 0, rms = 0;
  size_t failed_pixels = 0;
};

ColourDifference colour_difference(const FrameImages& a, const FrameImages& b, float fail) {
  double sum = 0, sum_sq = 0;
  ColourDifference d;
  for (size_t i = 0; i < a.color.size(); ++i) {
    bool failed = false;
    for (int c = 0; c < 3; ++c) {
      const double e = std::abs(double(a.color[i][c]) - double(b.color[i][c]));
      sum += e;
      sum_sq += e * e;
      failed = failed || e > fail;
    }
    d.failed_pixels += failed;
  }
  const double values = 3.0 * static_cast<double>(a.color.size());
  d.mean = sum / values;
  d.rms = std::sqrt(sum_sq / values);
  return d;
}

}  // namespace

Agreement compare_frames(const FrameImages& test, const FrameImages& reference, const std::vector<float>& instance_voxels) {
  if (test.width != reference.width || test.height != reference.height || test.color.empty())
    throw InternalError("compared frames differ in size or hold no pixels");
  const size_t pixels = test.color.size();
  size_t hit_agree = 0, id_candidates = 0, id_agree = 0;
  std::vector<double> depth_errors, voxel_errors;
  for (size_t i = 0; i < pixels; ++i) {
    const uint32_t a = test.instance_id[i], b = reference.instance_id[i];
    hit_agree += is_instance(a) == is_instance(b);
    if (is_instance(a) || is_instance(b)) {
      ++id_candidates;
      id_agree += a == b;
    }
    if (a == b && a != shading::NO_INSTANCE_VALUE && reference.depth[i] > 0.0f)
      depth_errors.push_back(std::abs(test.depth[i] - reference.depth[i]) / reference.depth[i]);
    if (a == b && is_instance(a) && a < instance_voxels.size() && instance_voxels[a] > 0.0f)
      voxel_errors.push_back(std::abs(test.depth[i] - reference.depth[i]) / instance_voxels[a]);
  }
  auto p99 = [](std::vector<double>& errors) {
    const size_t k = std::min(errors.size() - 1, static_cast<size_t>(0.99 * static_cast<double>(errors.size())));
    std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(k), errors.end());
    return errors[k];
  };
  Agreement result;
  result.hit_percent = 100.0 * static_cast<double>(hit_agree) / static_cast<double>(pixels);
  result.id_percent = id_candidates ? 100.0 * static_cast<double>(id_agree) / static_cast<double>(id_candidates) : 100.0;
  result.id_mismatches = id_candidates - id_agree;
  if (!depth_errors.empty()) result.depth_p99 = p99(depth_errors);
  if (!instance_voxels.empty()) result.depth_p99_voxels = voxel_errors.empty() ? 0.0 : p99(voxel_errors);
  const ColourDifference colour = colour_difference(test, reference, kPixelFailThreshold);
  result.mean_error = colour.mean;
  result.rms_error = colour.rms;
  result.psnr = colour.rms > 0.0 ? 20.0 * std::log10(1.0 / colour.rms) : std::numeric_limits<double>::infinity();  // peak 1
  result.over_threshold_percent = 100.0 * static_cast<double>(colour.failed_pixels) / static_cast<double>(pixels);
  return result;
}

std::string check_thresholds(const Agreement& g, const AgreementThresholds& t) {
  std::ostringstream failed;
  if (g.hit_percent < t.min_hit_percent) failed << " hit-mask " << g.hit_percent << "% < " << t.min_hit_percent << "%;";
  if (g.id_percent < t.min_id_percent && g.id_mismatches > t.max_id_mismatches) failed << " instance-id " << g.id_percent << "% < " << t.min_id_percent << "%;";
  if (g.depth_p99 > t.max_depth_p99) failed << " depth p99 " << g.depth_p99 << " > " << t.max_depth_p99 << ";";
  if (g.psnr < t.min_psnr) failed << " PSNR " << g.psnr << " dB < " << t.min_psnr << " dB;";
  std::string s = failed.str();
  if (!s.empty()) s = s.substr(1, s.size() - 2);
  return s;
}

}  // namespace sdfbench
