#pragma once
#include <filesystem>

#include "renderers/renderer.h"

namespace sdfbench {

// Fails early (before a long render) when `path` cannot be written: missing or read-only
// directory, or an image format OpenImageIO does not know.
void check_image_path(const std::filesystem::path& path, const char* what);

// Writes the shaded image (PNG, EXR, ... by extension) atomically: temp file + rename.
void write_color_image(const FrameImages& images, const std::filesystem::path& path);

// Writes the AOVs as one multi-channel float image (EXR): hit (1 where an instance was hit),
// depth, instance_id (-1: sky, -2: floor), primitive_id (-1: sky), N.x, N.y, N.z.
void write_aov_image(const FrameImages& images, const std::filesystem::path& path);

}  // namespace sdfbench
