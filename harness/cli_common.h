#pragma once
// Options and helpers shared by the sdfbench commands.
#include <functional>
#include <map>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "renderers/backend_registry.h"
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

// --device, --threads, --validate, --whitted-passes, --cache, --on-bad-cache and every backend's
// own parameters (add_backend_param_options)
void add_backend_options(CLI::App& command, BackendOptions& options);
// One flag per parameter of the registry's catalogue (renderers/backend_registry.h), its help
// naming the backends that take it; a value is checked and stored as it will be used.
// `include`, when given, picks which.
void add_backend_param_options(CLI::App& command, BackendParams& params,
                               const std::function<bool(const ParamSpec&)>& include = {});
// The same parameters as comma-separated lists (sweep axes): name -> the list as given.
void add_backend_param_list_options(CLI::App& command, std::map<std::string, std::string>& lists);
// A parameter's value as it is used and recorded; throws Error naming the flag and quoting `value`.
std::string parse_param_value(const ParamSpec& spec, const std::string& value);
// A sweep axis: the values of a comma-separated list, each as parse_param_value gives it; two that
// are one value ("8,008") are refused.
std::vector<std::string> parse_param_list(const ParamSpec& spec, const std::string& list);
// Throws Error naming the flag when a parameter given is taken by none of `backends`
// (backend_registry.h), and when --cache is given but none of them stores a structure.
void check_options_taken(const BackendOptions& options, const std::vector<std::string>& backends);
// "hash_cell=10 octree_depth=4 ..." (or "none"): the parameters `backend` uses, given or its
// defaults, as its CSV row records them.
std::string describe_params(const BackendInfo& backend, const BackendParams& given);

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
