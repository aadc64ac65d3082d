#pragma once
#include <filesystem>

#include "renderers/renderer.h"
#include "util/image_codec.h"

namespace sdfbench {

// Fails early (before a long render) when `path` cannot be written: missing or read-only
// directory, something other than a regular file in its place, or an extension that is not an
// image format sdfbench writes (util/image_codec.h).
void check_image_path(const std::filesystem::path& path, const char* what);
// The same for the AOV file, which must also be an EXR (the only format holding its 7 float channels).
void check_aov_path(const std::filesystem::path& path, const char* what);

// The writers encode in memory and write the bytes with write_file_atomically (util/atomic_file.h).

// The shaded image as the writers encode it (RGBA, display-encoded).
FloatImage color_image(const FrameImages& images);

// Writes the shaded image (PNG, EXR, ... by extension).
void write_color_image(const FrameImages& images, const std::filesystem::path& path);

// The value range of a heat map: `top` is yellow (and everything above it), `max` the largest value.
struct HeatmapRange {
  uint32_t top = 0, max = 0;
};

// Writes `values` (one per pixel, row-major, top row first) as an 8-bit colour-map image,
// atomically: 0 dark violet through blue and green to yellow at the 99th percentile, so that a
// few grazing rays do not darken the rest.
HeatmapRange write_heatmap(const std::vector<uint32_t>& values, uint32_t width, uint32_t height,
                           const std::filesystem::path& path);

// Scale of the difference map: a pixel's largest channel error at or above this is yellow; the
// agreement check counts a pixel as failed from kPixelFailThreshold (half of it) on.
inline constexpr float kDifferenceMapTop = 0.1f;

// The per-pixel difference of two frames' shaded images (the largest display-encoded channel error)
// as a colour map on a fixed scale, 0 dark violet to kDifferenceMapTop and above yellow, so that two
// maps compare by eye; a fixed scale, unlike write_heatmap's, keeps an identical frame dark.
FloatImage difference_map(const FrameImages& test, const FrameImages& reference);
void write_difference_map(const FrameImages& test, const FrameImages& reference, const std::filesystem::path& path);

// Writes the AOVs as one multi-channel float image (EXR): hit (1 where an instance was hit),
// depth, instance_id (-1: sky, -2: floor), primitive_id (-1: sky), N.x, N.y, N.z. Refuses any
// other extension than .exr.
void write_aov_image(const FrameImages& images, const std::filesystem::path& path);

}  // namespace sdfbench
