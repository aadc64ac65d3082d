#include "harness/image_agreement.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "renderers/shading/gpu_types.h"
#include "scenes/error.h"

namespace sdfbench {
namespace {

bool is_instance(uint32_t id) { return id < shading::FLOOR_INSTANCE_VALUE; }

OIIO::ImageBuf rgb_buffer(const FrameImages& f) {
  OIIO::ImageBuf buf(OIIO::ImageSpec(static_cast<int>(f.width), static_cast<int>(f.height), 3, OIIO::TypeDesc::FLOAT));
  std::vector<float> rgb(f.color.size() * 3);
  for (size_t i = 0; i < f.color.size(); ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + c] = f.color[i][c];
  buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, rgb.data());
  return buf;
}

}  // namespace

Agreement compare_frames(const FrameImages& test, const FrameImages& reference) {
  if (test.width != reference.width || test.height != reference.height || test.color.empty())
    throw Error("internal: compared frames differ in size or hold no pixels");
  const size_t pixels = test.color.size();
  size_t hit_agree = 0, id_candidates = 0, id_agree = 0;
  std::vector<double> depth_errors;
  for (size_t i = 0; i < pixels; ++i) {
    const uint32_t a = test.instance_id[i], b = reference.instance_id[i];
    hit_agree += is_instance(a) == is_instance(b);
    if (is_instance(a) || is_instance(b)) {
      ++id_candidates;
      id_agree += a == b;
    }
    if (a == b && a != shading::NO_INSTANCE_VALUE && reference.depth[i] > 0.0f)
      depth_errors.push_back(std::abs(test.depth[i] - reference.depth[i]) / reference.depth[i]);
  }
  Agreement result;
  result.hit_percent = 100.0 * static_cast<double>(hit_agree) / static_cast<double>(pixels);
  result.id_percent = id_candidates ? 100.0 * static_cast<double>(id_agree) / static_cast<double>(id_candidates) : 100.0;
  result.id_mismatches = id_candidates - id_agree;
  if (!depth_errors.empty()) {
    const size_t k = std::min(depth_errors.size() - 1, static_cast<size_t>(0.99 * static_cast<double>(depth_errors.size())));
    std::nth_element(depth_errors.begin(), depth_errors.begin() + static_cast<std::ptrdiff_t>(k), depth_errors.end());
    result.depth_p99 = depth_errors[k];
  }
  const OIIO::ImageBuf a = rgb_buffer(test), b = rgb_buffer(reference);
  const auto stats = OIIO::ImageBufAlgo::compare(a, b, kPixelFailThreshold, kPixelFailThreshold);
  // (stats.error only says that some pixel exceeded the fail threshold; nfail counts them.)
  result.mean_error = stats.meanerror;
  result.rms_error = stats.rms_error;
  result.psnr = stats.rms_error > 0.0 ? stats.PSNR : std::numeric_limits<double>::infinity();
  result.over_threshold_percent = 100.0 * static_cast<double>(stats.nfail) / static_cast<double>(pixels);
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
