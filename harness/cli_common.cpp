#include "harness/cli_common.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <algorithm>
#include <map>

#include "harness/list_option.h"
#include "renderers/shading/gpu_types.h"
#include "util/error.h"
#include "util/input_file.h"
#include "util/number_text.h"

namespace sdfbench {

CLI::Validator number_in(double lo, double hi, bool lo_open) {
  const std::string range = (lo_open ? "(" : "[") + six_digits(lo) + ", " + six_digits(hi) + "]";
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double v = 0.0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
          return "expected a number in " + range + ", got '" + text + "'";
        if (v < lo || v > hi || (lo_open && v == lo)) return "must be in " + range + ", got " + text;
        return std::string();
      },
      "FLOAT in " + range);
}

void check_image_size(ImageSize size, const std::string& what) {
  if (size.width < 1 || size.height < 1 || size.width > kMaxImageSide || size.height > kMaxImageSide)
    throw Error(what + ": width and height must be between 1 and " + std::to_string(kMaxImageSide));
  const uint64_t pixels = uint64_t(size.width) * size.height;
  if (pixels > kMaxImagePixels)
    throw Error(what + ": " + std::to_string(pixels) + " pixels, more than the limit of " +
                std::to_string(kMaxImagePixels) + " (8192x4096): the frame's images would need about " +
                describe_bytes(pixels * 44) + " each");
}

ImageSize parse_size(const std::string& text, const std::string& flag) {
  const std::string what = flag + " '" + (text.size() > 40 ? text.substr(0, 40) + "..." : text) + "'";
  const size_t x = text.find('x');
  auto parse = [&](const std::string& part) {
    uint64_t v = 0;
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), v);
    if (part.empty() || end != part.data() + part.size() || (ec != std::errc() && ec != std::errc::result_out_of_range))
      throw Error(what + ": expected WIDTHxHEIGHT, e.g. 320x180");
    if (ec == std::errc::result_out_of_range || v > kMaxImageSide)
      throw Error(what + ": width and height must be between 1 and " + std::to_string(kMaxImageSide));
    return static_cast<uint32_t>(v);
  };
  if (x == std::string::npos) throw Error(what + ": expected WIDTHxHEIGHT, e.g. 320x180");
  const ImageSize size{parse(text.substr(0, x)), parse(text.substr(x + 1))};
  check_image_size(size, what);
  return size;
}

void add_backend_options(CLI::App& command, BackendOptions& options) {
  command.add_option("--device", options.device,
                     "Vulkan device: lavapipe (default), gpu, an index or part of a name (see `sdfbench info`)");
  command.add_option("--threads", options.threads, "CPU threads for Embree (default: as many as lavapipe uses)")
      ->check(CLI::Range(1u, 1024u));
  command.add_flag("--validate", options.validation,
                   "enable VK_LAYER_KHRONOS_validation; any validation message makes the command fail");
  command.add_option_function<std::string>(
             "--whitted-passes",
             [&options](const std::string& value) {
               options.whitted_passes = value == "auto" ? std::nullopt : std::optional<bool>(value == "on");
             },
             "whitted on Vulkan: on = one ray per pixel per dispatch (for drivers with a loop cap), off = a pixel's "
             "whole ray tree in one invocation; auto (default): on only where `sdfbench info` finds a loop cap")
      ->check(CLI::IsMember({"auto", "on", "off"}));
  add_backend_param_options(command, options.params);
  command.add_option("--cache", options.cache.path,
                     "SDF structure cache file: loaded when valid for this scene and these parameters, else built and written")
      ->check([](const std::string& path) -> std::string {
        // Refused before the build, not after it when the cache is written: a FIFO would hang the
        // read and a device must never be replaced.
        std::error_code ec;
        const std::filesystem::file_status st = std::filesystem::status(path, ec);
        if (ec || !std::filesystem::exists(st) || std::filesystem::is_regular_file(st)) return "";
        if (std::filesystem::is_directory(st)) return "SDF cache '" + path + "' is a directory, not a file";
        return "SDF cache '" + path + "' is not a regular file (a FIFO, socket or device)";
      })
      ->group("SDF structures");
  command.add_option("--on-bad-cache", options.cache.on_bad, "an invalid or stale --cache file: refuse (default, an error) or rebuild")
      ->transform(CLI::CheckedTransformer(std::map<std::string, BadCachePolicy>{{"refuse", BadCachePolicy::Refuse},
                                                                                    {"rebuild", BadCachePolicy::Rebuild}},
                                          CLI::ignore_case))
      ->group("SDF structures");
}

namespace {

// "(default 10; sdf-hash: 1; taken by sdf-hash, sdf-octree, sdf-bricks, sdf-cpu)"
std::string param_help(const ParamSpec& spec) {
  std::string other_defaults;
  for (const BackendInfo& b : backends())
    for (const ParamSpec& own : b.params)
      if (own.name == spec.name && own.default_value != spec.default_value)
        other_defaults += "; " + b.name + ": " + own.default_value;
  return spec.help + " (default " + spec.default_value + other_defaults + "; taken by " + owners_of(spec.name) + ")";
}

const char* value_type(const ParamSpec& spec) {
  switch (spec.kind) {
    case ParamKind::Integer: return "INT";
    case ParamKind::Real: return spec.choices.empty() ? "REAL" : "REAL|WORD";
    case ParamKind::Choice: return "CHOICE";
    case ParamKind::Flag: return "0|1";
  }
  return "VALUE";
}

// A flag's value, parsed and checked once against its declaration (renderers/backend_params.h).
TypedParam parse_flag_value(const ParamSpec& spec, const std::string& value) {
  std::string why;
  const std::optional<TypedParam> typed = parse_param(spec, value, why);
  if (!typed) throw Error(flag_of(spec) + ": " + why);
  return *typed;
}

}  // namespace

std::string parse_param_value(const ParamSpec& spec, const std::string& value) { return parse_flag_value(spec, value).text; }

std::vector<std::string> parse_param_list(const ParamSpec& spec, const std::string& list) {
  std::vector<std::string> values;
  for (const std::string& text : split_list(list, flag_of(spec))) {
    const std::string value = parse_param_value(spec, text);
    if (std::find(values.begin(), values.end(), value) != values.end())
      throw Error(flag_of(spec) + " '" + list + "': '" + text + "' is listed twice" + (text == value ? "" : " (as '" + value + "')"));
    values.push_back(value);
  }
  return values;
}

void add_backend_param_options(CLI::App& command, BackendParams& params, const std::function<bool(const ParamSpec&)>& include) {
  for (const ParamSpec& spec : param_catalogue()) {
    if (include && !include(spec)) continue;
    if (spec.kind == ParamKind::Flag) {
      command.add_flag_function(flag_of(spec), [&params, name = spec.name](int64_t) { params.set(name, TypedParam{"1", true}); }, param_help(spec))
          ->group(spec.group);
      continue;
    }
    command
        .add_option_function<std::string>(
            flag_of(spec), [&params, spec](const std::string& value) { params.set(spec.name, parse_flag_value(spec, value)); },
            param_help(spec))
        ->type_name(value_type(spec))
        ->group(spec.group);
  }
}

void add_backend_param_list_options(CLI::App& command, std::map<std::string, std::string>& lists) {
  for (const ParamSpec& spec : param_catalogue())
    command
        .add_option_function<std::string>(
            flag_of(spec), [&lists, name = spec.name](const std::string& values) { lists[name] = values; },
            param_help(spec) + "; comma-separated values, each a configuration")
        ->type_name("LIST")
        ->group(spec.group);
}

void check_options_taken(const BackendOptions& options, const std::vector<std::string>& run_backends) {
  check_params_taken(options.params, run_backends);
  if (options.cache.path.empty()) return;
  for (const std::string& b : run_backends)
    if (backend_info(b).stores_structure) return;
  std::string stores;
  for (const BackendInfo& b : backends())
    if (b.stores_structure) stores += (stores.empty() ? "" : ", ") + b.name;
  throw Error("--cache stores the structures of " + stores + "; no backend of this run takes it");
}

std::string describe_params(const BackendInfo& backend, const BackendParams& given) {
  const std::map<std::string, std::string> recorded = recorded_params(backend, resolve_params(backend, given));
  std::string text;
  for (const ParamSpec& spec : backend.params)  // in the backend's order
    if (recorded.count(spec.name)) text += (text.empty() ? "" : " ") + spec.name + "=" + recorded.at(spec.name);
  return text.empty() ? "none" : text;
}

void add_mode_options(CLI::App& command, std::string& mode, std::optional<uint32_t>& max_depth) {
  command.add_option("--mode", mode, "primary | shadow | whitted")->capture_default_str();
  command.add_option("--max-depth", max_depth,
                     "whitted: deepest reflection/refraction bounce (default: the scene's render.max_depth)")
      ->check(CLI::Range(0u, MAX_DEPTH_LIMIT));
}

RenderMode parse_mode_option(const std::string& text) {
  const auto mode = parse_render_mode(text);
  if (!mode) throw Error("--mode '" + text + "': expected primary, shadow or whitted");
  return *mode;
}

std::string describe_mode(const FrameRequest& request, const Scene& scene) {
  if (request.mode != RenderMode::Whitted) return to_string(request.mode);
  return "whitted (max depth " + std::to_string(request.max_depth.value_or(scene.render.max_depth)) + ")";
}

ImageSize frame_size(const std::string& size_option, const Scene& scene) {
  if (!size_option.empty()) return parse_size(size_option);
  const ImageSize size{scene.render.width, scene.render.height};
  check_image_size(size, scene.name + ": render.width x render.height");
  return size;
}

std::string describe_scene(const Scene& scene) {
  const std::string implicits =
      scene.implicits.empty() ? "" : std::to_string(scene.implicits.size()) + " implicit objects, ";
  return scene.name + " (" + std::to_string(scene.instances.size()) + " instances, " + implicits +
         std::to_string(scene.triangle_count()) + " triangles)";
}

}  // namespace sdfbench
