// `sdfbench sweep`: every combination of one backend's parameters on one scene, each point with
// its build time, bytes, FPS, Mrays/s, counters and agreement. Every parameter a backend declares
// (renderers/backend_registry.h) is an axis, and so is an overlap: scene's k (--overlap).

#include <algorithm>
#include <map>

#include "harness/cli_common.h"
#include "harness/commands.h"
#include "harness/list_option.h"
#include "harness/overlap_axis.h"
#include "harness/run_options.h"
#include "scenes/scene_source.h"
#include "util/error.h"

namespace sdfbench {
namespace {

struct SweepArgs {
  std::string scene, backend = "sdf-octree", mode = "primary", size = "320x180", overlap;
  unsigned max_depth = 4;
  std::map<std::string, std::string> axes;  // parameter name -> comma-separated values, as given
  RunOptions run;
  BackendOptions options;
};

void run_sweep(SweepArgs args) {
  const BackendInfo& backend = backend_info(args.backend);
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
  // Every axis parsed and checked once (against this backend's own values), and the product
  // refused before anything is built.
  std::vector<std::pair<std::string, std::vector<TypedParam>>> axes;
  std::vector<std::pair<std::string, size_t>> axis_sizes;
  for (const auto& [name, list] : args.axes) {
    const ParamSpec& spec = catalogue_spec(name);
    if (!owns(backend, name))
      throw Error(flag_of(spec) + " is a parameter of " + owners_of(name) + "; --backend " + args.backend + " does not take it");
    std::vector<TypedParam> values;
    for (const std::string& value : parse_param_list(spec, list)) {
      BackendParams one;
      one.set(name, value);
      // Throws naming the flag for a value this backend refuses; the plan keeps the typed value.
      values.push_back(*resolve_params(backend, one).typed(name));
    }
    axis_sizes.emplace_back(flag_of(spec), values.size());
    axes.emplace_back(name, values);
  }
  check_options_taken(args.options, {args.backend});
  // --overlap: the scene's k varies slowest, so each scene is loaded once.
  std::vector<BenchConfig> plan = {base};
  if (!args.overlap.empty()) {
    plan.clear();
    for (const double k : parse_overlap_list(args.overlap)) {
      plan.push_back(base);
      plan.back().scene = with_overlap(args.scene, k);
    }
    axis_sizes.emplace(axis_sizes.begin(), "--overlap", plan.size());
  }
  check_plan_size(axis_sizes);
  for (const ParamSpec& spec : backend.params) {  // the backend's order: its first parameter varies slowest
    const auto axis = std::find_if(axes.begin(), axes.end(), [&](const auto& a) { return a.first == spec.name; });
    if (axis == axes.end()) continue;
    std::vector<BenchConfig> expanded;
    for (const BenchConfig& c : plan)
      for (const TypedParam& value : axis->second) {
        expanded.push_back(c);
        expanded.back().options.params.set(spec.name, value);
      }
    plan = std::move(expanded);
  }
  run_and_report(plan, args.run, scene_inputs(load_scene(args.scene)));
}

}  // namespace

void register_sweep_command(CLI::App& app) {
  auto args = std::make_shared<SweepArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sweep", "Sweep one backend's parameters (every combination of the lists given) on one scene");
  cmd->add_option("--scene", args->scene, "scene descriptor (.json) or generator, e.g. thesis:bunny:1000")->required();
  cmd->add_option("--backend", args->backend, "one of " + backend_list())->capture_default_str();
  cmd->add_option("--mode", args->mode, "primary | shadow | whitted")->capture_default_str();
  cmd->add_option("--size", args->size, "WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--max-depth", args->max_depth, "whitted recursion depth")->capture_default_str()->check(CLI::Range(0u, 16u));
  cmd->add_option("--overlap", args->overlap,
                  "with an overlap:<mesh>:<count>:<k> --scene: its k as an axis, comma-separated, 1..64 (the scene's k replaced)");
  add_backend_param_list_options(*cmd, args->axes);
  add_run_options(*cmd, args->run);
  cmd->add_option("--device", args->options.device, "Vulkan device: lavapipe (default), gpu, an index or a name");
  cmd->add_option("--threads", args->options.threads, "CPU threads (Embree reference, sdf-cpu)")->check(CLI::Range(1u, 1024u));
  cmd->add_flag("--validate", args->options.validation, "enable the Vulkan validation layer");
  cmd->callback([args] { run_sweep(*args); });
}

}  // namespace sdfbench
