// `sdfbench table`: the thesis' FPS tables 6.1-6.3 over meshes x object counts, every backend
// beside them in the same mode, thesis values alongside.
#include "harness/cli_common.h"
#include "harness/commands.h"
#include "harness/list_option.h"
#include "harness/run_options.h"
#include "harness/thesis_tables.h"
#include "scenes/mesh.h"
#include "scenes/mesh_resize.h"
#include "util/error.h"

namespace sdfbench {
namespace {

struct TableArgs {
  std::string tables = "all", size, meshes = "bunny,teapot,monkey,sphere", objects = "1,10,100,1000",
              backends = default_table_backends(), mode, triangles;
  unsigned max_depth = 4;
  bool quick = false;
  RunOptions run;
  BackendOptions options;
};

std::vector<BenchConfig> table_plan(const TableArgs& args) {
  std::vector<const ThesisTableConfig*> tables;
  for (const std::string& id : args.tables == "all" ? std::vector<std::string>{"6.1", "6.2", "6.3"} : split_list(args.tables, "--table")) {
    const ThesisTableConfig* t = find_thesis_table(id);
    if (!t) throw Error("--table '" + id + "': expected 6.1, 6.2, 6.3 or all");
    tables.push_back(t);
  }
  // The modes to run: each selected table's own (or --mode for all of them).
  std::vector<RenderMode> modes;
  for (const ThesisTableConfig* t : tables) {
    const RenderMode m = args.mode.empty() ? t->mode : parse_mode_option(args.mode);
    if (std::find(modes.begin(), modes.end(), m) == modes.end()) modes.push_back(m);
  }
  const std::vector<std::string> meshes = split_list(args.meshes, "--meshes");
  for (const std::string& mesh : meshes)
    if (builtin_mesh_path(mesh).empty()) throw Error("--meshes: '" + mesh + "' is not a thesis mesh (bunny, teapot, monkey, sphere)");
  // --triangles: every mesh at each size (thesis:<mesh>@<n>:<count>), the mesh-size axis.
  std::vector<std::string> mesh_specs;
  for (const std::string& mesh : meshes) {
    if (args.triangles.empty()) mesh_specs.push_back(mesh);
    for (const uint32_t n : args.triangles.empty() ? std::vector<uint32_t>{} : parse_list<uint32_t>(args.triangles, "--triangles")) {
      if (n < kMinResizedTriangles || n > kMaxResizedTriangles)
        throw Error("--triangles: " + std::to_string(n) + " is outside " + std::to_string(kMinResizedTriangles) + ".." +
                    std::to_string(kMaxResizedTriangles));
      mesh_specs.push_back(mesh + "@" + std::to_string(n));
    }
  }
  const std::vector<size_t> counts = parse_list<size_t>(args.objects, "--objects");
  for (size_t count : counts)
    if (count == 0) throw Error("--objects: counts must be >= 1");
  const std::vector<std::string> backends = split_list(args.backends, "--backends");
  // Unknown names fail here, before hours of work; a device a backend cannot use (vk-rt without
  // ray tracing) makes its rows ERROR rows.
  for (const std::string& b : backends) check_backend_name(b);
  check_options_taken(args.options, backends);
  const ImageSize size = parse_size(args.size.empty() ? (args.quick ? "160x90" : "1280x720") : args.size);
  check_plan_size({{"--meshes x --triangles", mesh_specs.size()}, {"--objects", counts.size()}, {"modes", modes.size()},
                   {"--backends", backends.size()}});

  std::vector<BenchConfig> plan;
  for (const std::string& mesh : mesh_specs)
    for (size_t count : counts) {
      for (RenderMode mode : modes)
        for (const std::string& backend : backends) {
          BenchConfig c;
          for (const ThesisTableConfig* t : tables)
            if (t->backend == backend && t->mode == mode) c.table = t->id;
          c.scene = "thesis:" + mesh + ":" + std::to_string(count);
          c.backend = backend;
          c.mode = mode;
          c.size = size;
          c.max_depth = args.max_depth;
          c.options = args.options;
          plan.push_back(c);
        }
    }
  return plan;
}

void run_table(TableArgs args) {
  if (args.quick) {
    // The README's first command: a few minutes on 2 cores. Explicit flags still win.
    if (args.meshes == "bunny,teapot,monkey,sphere") args.meshes = "bunny,sphere";
    if (args.objects == "1,10,100,1000") args.objects = "1,10,100";
    args.run.settings.frames = std::min(args.run.settings.frames, 3u);
    args.run.settings.budget_s = std::min(args.run.settings.budget_s, 20.0);
  }
  args.run.settings.check_size = parse_size(args.run.check_size);
  args.run.plan();  // a bad --shard fails before the plan is built
  std::vector<NamedPath> inputs;  // the thesis meshes the tables read
  for (const std::string& mesh : split_list(args.meshes, "--meshes")) inputs.push_back({"the thesis mesh", builtin_mesh_path(mesh)});
  run_and_report(table_plan(args), args.run, inputs);
}

}  // namespace

void register_table_command(CLI::App& app) {
  auto args = std::make_shared<TableArgs>();
  CLI::App* cmd = app.add_subcommand("table", "Reproduce the thesis' FPS tables 6.1-6.3 (meshes x object counts), every "
                                              "backend beside them, thesis values alongside");
  cmd->add_option("--table", args->tables, "6.1, 6.2, 6.3 (comma-separated) or all")->capture_default_str();
  cmd->add_option("--size", args->size, "WIDTHxHEIGHT (default 1280x720, the thesis'; --quick: 160x90)");
  cmd->add_option("--meshes", args->meshes, "thesis meshes")->capture_default_str();
  cmd->add_option("--objects", args->objects, "object counts")->capture_default_str();
  cmd->add_option("--triangles", args->triangles,
                  "mesh sizes: every mesh resized to each of these triangle counts (e.g. 1000,16000,256000; default: as they are)");
  cmd->add_option("--backends", args->backends, "backends run in every table's mode")->capture_default_str();
  cmd->add_option("--mode", args->mode, "run every table in this mode instead of the thesis' (whitted for 6.1/6.2, shadow for 6.3)");
  cmd->add_option("--max-depth", args->max_depth, "whitted recursion depth")->capture_default_str()->check(CLI::Range(0u, 16u));
  cmd->add_flag("--quick", args->quick,
                "small version (bunny and sphere, 1/10/100 objects, 160x90, 3 frames, 20 s budget): minutes on 2 cores");
  add_run_options(*cmd, args->run);
  add_backend_options(*cmd, args->options);
  cmd->callback([args] { run_table(*args); });
}

}  // namespace sdfbench
