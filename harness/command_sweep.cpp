// `sdfbench sweep`: the full grid of SDF structure parameters on one scene, each point with its
// build time, bytes, FPS, Mrays/s, counters and agreement.

#include <map>

#include "harness/cli_common.h"
#include "harness/commands.h"
#include "harness/list_option.h"
#include "harness/run_options.h"
#include "scenes/scene_source.h"
#include "util/error.h"

namespace sdfbench {
namespace {

struct SweepArgs {
  std::string scene, backend = "sdf-octree", mode = "primary", size = "320x180", hash_cells = "10", depths = "4",
              min_objects = "1", mesh_cells = "0", over_relax = "1", cell_bound = "0", storage_tables = "0";
  unsigned max_depth = 4;
  std::map<std::string, std::string> params;  // the backend family's own parameters: name -> comma-separated values
  RunOptions run;
  BackendOptions options;
};

void run_sweep(SweepArgs args) {
  if (args.backend.rfind("sdf-", 0) != 0) throw Error("--backend '" + args.backend + "': a sweep varies SDF structures (sdf-octree, sdf-hash, sdf-bricks, sdf-global, sdf-cpu)");
  check_backend_name(args.backend);
  args.run.settings.check_size = parse_size(args.run.check_size);
  args.run.plan();  // a bad --shard fails before the plan is built
  BenchConfig base;
  base.table = "sweep";
  base.scene = args.scene;
  base.backend = args.backend;
  base.mode = parse_mode_option(args.mode);
  base.size = parse_size(args.size);
  base.max_depth = args.max_depth;
  base.options = args.options;
  base.options.hash_cell_given = true;  // the sweep's hash cell is what the row says, also for sdf-hash
  // Every axis parsed and checked once, and the product refused before anything is built.
  const std::vector<float> cells = parse_list<float>(args.hash_cells, "--hash-cell");
  const std::vector<unsigned> depths = parse_list<unsigned>(args.depths, "--octree-depth");
  const std::vector<unsigned> min_objects = parse_list<unsigned>(args.min_objects, "--octree-min-objects");
  const std::vector<float> mesh_cells = parse_list<float>(args.mesh_cells, "--mesh-cell");
  const std::vector<float> omegas = parse_list<float>(args.over_relax, "--over-relax");
  const std::vector<unsigned> bounds = parse_list<unsigned>(args.cell_bound, "--cell-bound");
  const std::vector<unsigned> storages = parse_list<unsigned>(args.storage_tables, "--storage-tables");
  for (unsigned n : min_objects)
    if (n < 1) throw Error("--octree-min-objects: values must be >= 1");
  for (float omega : omegas)
    if (!(omega >= 1.0f && omega <= 1.95f)) throw Error("--over-relax: values must be in [1, 1.95]");
  for (unsigned bound : bounds)
    if (bound > 1) throw Error("--cell-bound: values must be 0 (off) or 1 (on)");
  for (unsigned storage : storages)
    if (storage > 1) throw Error("--storage-tables: values must be 0 (texel buffers) or 1 (storage buffers)");
  // The backend family's own parameters (renderers/backend_params.h) are axes too; one given for
  // another family would change nothing.
  std::vector<std::pair<std::string, std::vector<std::string>>> param_axes;
  std::vector<std::pair<std::string, size_t>> axis_sizes = {
      {"--hash-cell", cells.size()},   {"--octree-depth", depths.size()}, {"--octree-min-objects", min_objects.size()},
      {"--mesh-cell", mesh_cells.size()}, {"--over-relax", omegas.size()}, {"--cell-bound", bounds.size()},
      {"--storage-tables", storages.size()}};
  for (const ParamSpec& spec : param_specs()) {
    const auto given = args.params.find(spec.name);
    if (given == args.params.end()) continue;
    if (!belongs_to(spec, args.backend))
      throw Error(flag_of(spec) + " is a parameter of " + families_of(spec) + ", not of --backend " + args.backend);
    std::vector<std::string> values = split_list(given->second, flag_of(spec));
    BackendParams check;
    for (std::string& value : values) {
      check.set(spec.name, value);  // throws naming the flag
      value = check.get(spec.name);
    }
    axis_sizes.emplace_back(flag_of(spec), values.size());
    param_axes.emplace_back(spec.name, values);
  }
  check_plan_size(axis_sizes);
  std::vector<BenchConfig> plan;
  for (float cell : cells)
    for (unsigned depth : depths)
      for (unsigned min_object_count : min_objects)
        for (float mesh_cell : mesh_cells)
          for (float omega : omegas)
            for (unsigned bound : bounds)
              for (unsigned storage : storages) {
                BenchConfig c = base;
                c.options.tracing.cell_bound = bound == 1;
                c.options.tracing.storage_tables = storage == 1;
                c.options.tracing.over_relax = omega;
                c.options.scene_hash.hash_cell = cell;
                c.options.scene_hash.octree_depth = depth;
                c.options.scene_hash.octree_min_objects = min_object_count;
                c.options.mesh_grid.cell_size = mesh_cell;
                sdf::validate(c.options.scene_hash);
                plan.push_back(c);
              }
  for (const auto& [name, values] : param_axes) {
    std::vector<BenchConfig> expanded;
    for (const BenchConfig& c : plan)
      for (const std::string& value : values) {
        expanded.push_back(c);
        expanded.back().options.params.set(name, value);
      }
    plan = std::move(expanded);
  }
  run_and_report(plan, args.run, scene_inputs(load_scene(args.scene)));
}

}  // namespace

void register_sweep_command(CLI::App& app) {
  auto args = std::make_shared<SweepArgs>();
  CLI::App* cmd = app.add_subcommand("sweep", "Sweep SDF structure parameters (every combination) on one scene");
  cmd->add_option("--scene", args->scene, "scene descriptor (.json) or generator, e.g. thesis:bunny:1000")->required();
  cmd->add_option("--backend", args->backend, "SDF backend")->capture_default_str();
  cmd->add_option("--mode", args->mode, "primary | shadow | whitted")->capture_default_str();
  cmd->add_option("--size", args->size, "WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--max-depth", args->max_depth, "whitted recursion depth")->capture_default_str()->check(CLI::Range(0u, 16u));
  cmd->add_option("--hash-cell", args->hash_cells, "hash cell sizes, comma-separated")->capture_default_str();
  cmd->add_option("--octree-depth", args->depths, "octree depths, comma-separated")->capture_default_str();
  cmd->add_option("--octree-min-objects", args->min_objects, "octree min objects, comma-separated")->capture_default_str();
  cmd->add_option("--mesh-cell", args->mesh_cells, "mesh grid cell sizes, comma-separated (0: from cells per extent)")
      ->capture_default_str();
  cmd->add_option("--cells-per-extent", args->options.mesh_grid.cells_per_extent,
                  "mesh grid cells along the mesh's largest extent (with --mesh-cell 0)")
      ->capture_default_str()->check(CLI::Range(1u, 1024u));
  add_tracing_options(*cmd, args->options.tracing, "SDF tracing");
  cmd->remove_option(cmd->get_option("--over-relax"));  // axes here: lists
  cmd->remove_option(cmd->get_option("--cell-bound"));
  cmd->remove_option(cmd->get_option("--storage-tables"));
  cmd->add_option("--cell-bound", args->cell_bound, "cell bounds off (0) and/or on (1), comma-separated")
      ->capture_default_str()->group("SDF tracing");
  cmd->add_option("--storage-tables", args->storage_tables,
                  "the structure's tables in texel buffers (0) and/or storage buffers (1), comma-separated")
      ->capture_default_str()->group("SDF tracing");
  cmd->add_option("--over-relax", args->over_relax,
                  "over-relaxation factors, comma-separated (1: the thesis' plain sphere tracing; Keinert et al. 2014)")
      ->capture_default_str()->group("SDF tracing");
  for (const ParamSpec& spec : param_specs())
    cmd->add_option_function<std::string>(
           flag_of(spec), [args, name = spec.name](const std::string& values) { args->params[name] = values; },
           spec.help + "; comma-separated values (default " + spec.default_value + ")")
        ->group(families_of(spec));
  add_run_options(*cmd, args->run);
  cmd->add_option("--device", args->options.device, "Vulkan device: lavapipe (default), gpu, an index or a name");
  cmd->add_option("--threads", args->options.threads, "CPU threads (Embree reference, sdf-cpu)")->check(CLI::Range(1u, 1024u));
  cmd->add_flag("--validate", args->options.validation, "enable the Vulkan validation layer");
  cmd->callback([args] { run_sweep(*args); });
}

}  // namespace sdfbench
