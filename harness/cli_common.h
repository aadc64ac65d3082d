#pragma once
// Options and helpers shared by the sdfbench commands.
#include <optional>
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
// --max-steps, --hit-epsilon, --hit (add_structure_options includes them).
void add_tracing_options(CLI::App& command, sdf::SphereTraceParams& tracing, const std::string& group);

// --mode primary|shadow|whitted and --max-depth (whitted recursion limit; default: the scene's)
void add_mode_options(CLI::App& command, std::string& mode, std::optional<uint32_t>& max_depth);
// The --mode value; throws Error naming the flag for anything else.
RenderMode parse_mode_option(const std::string& text);
// "primary", "shadow" or "whitted (max depth N)", as the frame will render.
std::string describe_mode(const FrameRequest& request, const Scene& scene);

// The size a command renders at: --size if given, else the scene's render settings.
ImageSize frame_size(const std::string& size_option, const Scene& scene);

std::string describe_scene(const Scene& scene);

}  // namespace sdfbench
