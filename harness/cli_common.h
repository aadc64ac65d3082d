#pragma once
// Options and helpers shared by the sdfbench commands.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "renderers/renderer.h"
#include "scenes/scene.h"
#include "util/image_codec.h"

namespace sdfbench {

struct ImageSize {
  uint32_t width = 0, height = 0;
};

// Frame sizes every command accepts: each side up to kMaxImageSide (util/image_codec.h: what the
// image files sdfbench reads and writes allow), and at most kMaxImagePixels
// in all, so that the frame's images (~44 bytes per pixel for each one held, more on the
// backend's side) are refused up front rather than running out of memory mid-render.
inline constexpr uint64_t kMaxImagePixels = uint64_t(1) << 25;  // 8192x4096; 7680x4320 fits

// "WxH" within the limits above; throws Error naming `flag` otherwise.
ImageSize parse_size(const std::string& text, const std::string& flag = "--size");
// Throws Error unless `size` is within the limits above; `what` names where it came from.
void check_image_size(ImageSize size, const std::string& what);

// A CLI11 check for a finite number in [lo, hi] (or (lo, hi] when lo_open), whose message names
// the range in a few digits (CLI11's own prints doubles' limits in full: 309 digits).
CLI::Validator number_in(double lo, double hi, bool lo_open = false);

// --device, --threads, --validate and the structure options below
void add_backend_options(CLI::App& command, BackendOptions& options);
// The flags of every backend family's own parameters (renderers/backend_params.h), grouped by family.
void add_backend_param_options(CLI::App& command, BackendParams& params);
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
