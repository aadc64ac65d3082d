#pragma once
#include <optional>
#include <vector>
// How closely a backend's frame matches a reference frame (docs/design.md, "Image agreement").
#include <string>

#include "renderers/renderer.h"

namespace sdfbench {

struct Agreement {
  double hit_percent = 0;        // pixels whose instance-hit mask agrees, over all pixels
  double id_percent = 0;         // same instance id, over pixels where either hit an instance
  size_t id_mismatches = 0;      // pixels where either hit an instance and the ids differ
  double depth_p99 = 0;          // 99th percentile of |t - t_ref| / t_ref where both hit the same thing
  // Given the test's voxel per instance (a sampled field): the 99th percentile of |t - t_ref| in
  // voxels of the instance hit, where both hit the same instance.
  std::optional<double> depth_p99_voxels;
  double mean_error = 0;         // shaded image (display-encoded RGB), as OpenImageIO compare
  double rms_error = 0;
  double psnr = 0;               // dB; infinity for identical images
  double over_threshold_percent = 0;  // pixels with a channel error > kPixelFailThreshold
};

struct AgreementThresholds {
  double min_hit_percent = 99.5;
  double min_id_percent = 99.0;
  // ... unless at most this many pixels differ: a single object can cover only ~60 pixels of a
  // check image, where one silhouette pixel is already 1.6 %.
  size_t max_id_mismatches = 2;
  double max_depth_p99 = 1e-3;
  double min_psnr = 30.0;
};

inline constexpr float kPixelFailThreshold = 0.05f;

Agreement compare_frames(const FrameImages& test, const FrameImages& reference,
                         const std::vector<float>& instance_voxels = {});

// Empty when every threshold holds, else a list of what failed.
std::string check_thresholds(const Agreement& agreement, const AgreementThresholds& thresholds);

}  // namespace sdfbench
