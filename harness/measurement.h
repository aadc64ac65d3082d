#pragma once
// One benchmark measurement = one CSV row (README, "CSV columns"): the configuration that
// produced it, its figures, its image agreement with the reference and where it ran.
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "harness/csv.h"
#include "renderers/work_counters.h"

namespace sdfbench {

struct Measurement {
  // configuration
  size_t run_index = 0;  // position in the run's configuration list (shards and merge keep it)
  std::string run_id;    // digest of the run's whole configuration list: every shard of one run has it
  std::string table;     // thesis table this row reproduces ("6.1", "6.2", "6.3"), "sweep", or empty
  std::string scene, mesh;
  size_t triangles = 0, objects = 0;
  // the mean number of instance boxes over a point of their union (scenes/overlap_layout.h,
  // measured_overlap): about 1 for the thesis layout, k for an overlap:<mesh>:<count>:<k> scene
  std::optional<double> overlap;
  std::string backend, mode;
  unsigned max_depth = 0;
  unsigned width = 0, height = 0;
  // the parameters the row's backend owns (renderers/backend_registry.h), by name, as it used
  // them; the CSV has a column for every backend's, empty where the row's backend has no such
  // parameter
  std::map<std::string, std::string> backend_params;
  // the run's methodology, as requested (--frames, --warmup, --budget-s, --reference, --device, ...)
  unsigned requested_frames = 0, warmup = 0;
  double budget_s = 0;
  // the structure cache (--cache, --on-bad-cache: "refuse" or "rebuild"; empty without a cache)
  std::string cache, on_bad_cache;
  std::string reference, requested_device, whitted_passes;  // whitted_passes: "auto", "on" or "off"
  bool validate = false;
  // timing
  unsigned frames = 0;  // timed frames actually run (fewer than requested_frames when the budget cut them)
  std::string clock;  // "device" (GPU timestamps) or "wall"
  double ms_median = 0, ms_min = 0, ms_max = 0, ms_wall_median = 0, fps = 0, mrays_per_s = 0, rays_per_pixel = 0;
  // work counters of the instrumented check frame, per ray, by COUNTER_* id (renderers/work_counters.h);
  // empty: the backend has no such counter
  std::array<std::optional<double>, COUNTER_KINDS> per_ray;
  double prepare_ms = 0;                                 // renderer prepare(): structure build or cache load + upload
  std::optional<double> build_ms, structure_bytes;       // built structures (SDF, BVH)
  std::optional<double> tree_sah, tree_epo, tree_nodes;  // a BVH's quality (renderers/bvh/bvh_quality.h)
  std::string backend_resolved;  // what the backend chose for its "auto" parameters (StructureStats::resolved)
  // agreement with the reference backend at the check size
  std::string check_size;
  std::optional<double> hit_agreement, id_agreement, psnr;
  // relative depth error (p99) where both hit the same instance; a sampled field's also in its voxels
  std::optional<double> depth_p99, depth_p99_voxels;
  std::string agreement;  // "ok", "reference", "DISAGREE: <what>", "TRUNCATED: <n> pixels" or "ERROR: <message>",
                          // all but ERROR possibly followed by " (N validation messages)" (harness/row_verdict.h reads it)
  bool budget_cut = false;
  // how busy the machine was over the timed frames (util/machine_load.h); empty where /proc is unreadable
  std::optional<double> load_avg, cpu_steal_pct, cpu_other_pct;
  std::optional<bool> busy;
  // the check images kept for the row (--keep-images): the backend's frame, the reference's and
  // their difference map, PNG, relative to the CSV's folder (to the working folder without --csv)
  std::string frame_image, reference_image, diff_image;
  // where
  std::string device, driver, cpu;
  std::string embree;  // Embree's version ("3.13.5", "4.3.3"): the reference backend and the bvh builder
  unsigned threads = 0;
  std::string commit;
};

// The columns, the backends' parameters (the registry's catalogue) among them: call after every
// backend is registered.
const std::vector<std::string>& measurement_columns();
// The work counters' columns, by COUNTER_* id: "<name>_per_ray".
const std::array<std::string, COUNTER_KINDS>& counter_columns();
// A number as the CSV writes it: 6 significant digits, "inf" and "-inf".
std::string csv_number(double v);
std::vector<std::string> to_csv_fields(const Measurement& m);

// The columns that identify a configuration: every parameter that changes a measurement, so a
// rerun with other settings is another configuration. Resume skips rows whose key is already in
// the file (and refuses rows of another run), merge refuses two files with the same key.
const std::vector<std::string>& configuration_key_columns();
std::string configuration_key(const std::vector<std::string>& fields, const std::vector<std::string>& columns);
std::string configuration_key(const Measurement& m);

// What separates the rows of two runs (for messages, when their run_ids differ): the first key
// column that differs at a run_index both have, else a run-wide setting that differs ("width
// '32' in 'a.csv', '320' in 'b.csv'"), else that they list other configurations (an example).
std::string run_difference(const CsvTable& a, const CsvTable& b);

// Row `row` (0-based) of `table`'s run_index; throws Error naming `source`, the row and the
// column when it is not a non-negative integer.
size_t row_run_index(const CsvTable& table, size_t row, const std::string& source);

}  // namespace sdfbench
