#pragma once
// Options and helpers shared by the sdfbench commands.
#include <string>

#include <CLI/CLI.hpp>

#include "renderers/renderer.h"
#include "scenes/scene.h"

namespace sdfbench {

struct ImageSize {
  uint32_t width = 0, height = 0;
};

// "WxH", both in [1, 16384]; throws Error otherwise.
ImageSize parse_size(const std::string& text);

// --device, --threads, --validate and the structure options below
void add_backend_options(CLI::App& command, BackendOptions& options);
// --mesh-cell, --cells-per-extent, --hash-cell, --octree-*, --lists, --max-steps, --hit-epsilon
void add_structure_options(CLI::App& command, BackendOptions& options);

// "primary|shadow" option; whitted arrives with the SDF backends issue.
RenderMode parse_mode_option(const std::string& text);

// The size a command renders at: --size if given, else the scene's render settings.
ImageSize frame_size(const std::string& size_option, const Scene& scene);

std::string describe_scene(const Scene& scene);

}  // namespace sdfbench
