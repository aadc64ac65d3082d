#include "harness/cli_common.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <map>

#include "renderers/shading/gpu_types.h"
#include "util/error.h"
#include "util/input_file.h"

namespace sdfbench {

namespace {

std::string short_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

}  // namespace

CLI::Validator number_in(double lo, double hi, bool lo_open) {
  const std::string range = (lo_open ? "(" : "[") + short_number(lo) + ", " + short_number(hi) + "]";
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
  add_structure_options(command, options);
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
      ->transform(CLI::CheckedTransformer(std::map<std::string, sdf::BadCachePolicy>{{"refuse", sdf::BadCachePolicy::Refuse},
                                                                                    {"rebuild", sdf::BadCachePolicy::Rebuild}},
                                          CLI::ignore_case))
      ->group("SDF structures");
}

void add_backend_param_options(CLI::App& command, BackendParams& params) {
  for (const ParamSpec& spec : param_specs()) {
    command
        .add_option_function<std::string>(
            flag_of(spec), [&params, name = spec.name](const std::string& value) { params.set(name, value); },
            spec.help + " (default " + spec.default_value + ")")
        ->check(CLI::Validator([spec](std::string& value) { return check_param_value(spec, value); },
                               spec.positive_real ? "REAL" : spec.choices.empty() ? "INT" : "CHOICE"))
        ->group(families_of(spec));
  }
}

void add_structure_options(CLI::App& command, BackendOptions& options) {
  const std::string group = "SDF structures";
  command.add_option("--mesh-cell", options.mesh_grid.cell_size, "mesh distance grid cell size in mesh units (0: from --cells-per-extent)")
      ->capture_default_str()->check(number_in(0.0, 1e30))->group(group);
  command.add_option("--cells-per-extent", options.mesh_grid.cells_per_extent, "mesh grid cells along the mesh's largest extent")
      ->capture_default_str()->check(CLI::Range(1u, 1024u))->group(group);
  command.add_flag("--fixed-grid", [&options](int64_t) { options.mesh_grid.scale_with_triangles = false; },
                   "keep --cells-per-extent for meshes over 8192 triangles too (default: finer with the triangle count, "
                   "far cells as bounds; docs/measured.md, \"Large meshes\")")
      ->group(group);
  command.add_option("--hash-cell", options.scene_hash.hash_cell,
                     "scene hash cell size (thesis: 10 with octree, 1 without; sdf-hash defaults to 1)")
      ->capture_default_str()->check(number_in(1e-30, 1e30))->group(group)
      ->each([&options](const std::string&) { options.hash_cell_given = true; });
  command.add_option("--octree-depth", options.scene_hash.octree_depth, "octree depth per hash cell (0: hash only)")
      ->capture_default_str()->check(CLI::Range(0u, 16u))->group(group);
  command.add_option("--octree-min-objects", options.scene_hash.octree_min_objects, "octree leaf when a node lists <= this many instances")
      ->capture_default_str()->check(CLI::Range(1u, 1000000u))->group(group);
  command.add_option("--octree-min-size", options.scene_hash.octree_min_size, "octree leaf when a node's edge is <= this (thesis: 1)")
      ->capture_default_str()->check(number_in(1e-30, 1e30))->group(group);
  command.add_option("--lists", options.scene_hash.lists, "instance lists: exact (default) or thesis (influence AABB)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, sdf::ListRule>{{"exact", sdf::ListRule::Exact},
                                                                              {"thesis", sdf::ListRule::Thesis}},
                                          CLI::ignore_case))
      ->group(group);
  command.add_option_function<uint64_t>(
             "--max-structure-mb",
             [&options](uint64_t mb) { options.mesh_grid.max_bytes = options.scene_hash.max_bytes = mb << 20; },
             "memory cap of each SDF structure (a mesh grid's lists, the scene hash's octrees): a build that grows past "
             "it stops with an error (default " + std::to_string(sdf::kDefaultMaxStructureBytes >> 20) + ")")
      ->check(CLI::Range(uint64_t(1), uint64_t(16384)))->group(group);
  add_tracing_options(command, options.tracing, group);
}

void add_tracing_options(CLI::App& command, sdf::SphereTraceParams& tracing, const std::string& group) {
  command.add_option("--max-steps", tracing.max_steps, "sphere-tracing steps per ray")
      ->capture_default_str()->check(CLI::Range(1u, 1000000u))->group(group);
  command.add_option("--hit-epsilon", tracing.hit_epsilon, "--hit thesis: sphere-tracing hit distance, relative to the scene size (beyond 1e-2 objects blur and vanish)")
      ->capture_default_str()->check(number_in(1e-8, 1e-2))->group(group);
  command.add_option("--hit-footprint", tracing.footprint,
                     "--hit exact: hit distance as a fraction of a pixel's footprint at the ray's length")
      ->capture_default_str()->check(number_in(1e-4, 1.0))->group(group);
  command.add_option("--over-relax", tracing.over_relax,
                     "over-relaxed sphere tracing (Keinert et al. 2014): steps of this x the distance, checked and undone "
                     "where they may have jumped a surface; 1 (default): the thesis' plain sphere tracing")
      ->capture_default_str()->check(number_in(1.0, 1.95))->group(group);
  command.add_flag("--cell-bound", tracing.cell_bound,
                   "Vulkan SDF kernels: a step from an octree leaf (hash cell) that no listed instance's box comes "
                   "near crosses it without evaluating an instance (off: the thesis' step everywhere)")
      ->group(group);
  command.add_flag("--storage-tables", tracing.storage_tables,
                   "Vulkan SDF kernels: the structure's tables in storage buffers instead of texel buffers (the same "
                   "data and images; which is faster depends on the device)")
      ->group(group);
  command.add_option("--hit", tracing.hit,
                     "SDF hits: exact (default: the ray's crossing with the triangles listed where it converged) or "
                     "thesis (the converged point, the closest point's normal and uv); sdf-bricks and sdf-global: exact or field (the sampled "
                     "field's own crossing and gradient normal, its accuracy in the row)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, sdf::HitMode>{{"exact", sdf::HitMode::exact},
                                                                             {"thesis", sdf::HitMode::thesis},
                                                                             {"field", sdf::HitMode::field}},
                                          CLI::ignore_case))
      ->group(group);
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
