#include "harness/measurement.h"

#include <cmath>
#include <cstdio>

namespace sdfbench {
namespace {

std::string number(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}
std::string number(const std::optional<double>& v) { return v ? number(*v) : ""; }

const std::vector<std::string> kKeyColumns = {"table", "scene", "backend", "mode", "max_depth", "width", "height",
                                              "hash_cell", "octree_depth", "octree_min_objects", "mesh_cell", "hit"};

}  // namespace

const std::vector<std::string>& measurement_columns() {
  static const std::vector<std::string> columns = {
      "run_index", "table", "scene", "mesh", "triangles", "objects", "backend", "mode", "max_depth", "width", "height",
      "hash_cell", "octree_depth", "octree_min_objects", "mesh_cell", "hit", "frames", "clock", "ms_median", "ms_min", "ms_max",
      "ms_wall_median", "fps", "mrays_per_s", "rays_per_pixel", "steps_per_ray", "instance_evals_per_ray",
      "triangle_evals_per_ray", "aabb_tests_per_ray", "triangle_tests_per_ray", "out_of_steps_per_ray", "prepare_ms", "build_ms", "structure_bytes", "check_size", "hit_agreement",
      "id_agreement", "psnr", "agreement", "budget_cut", "device", "driver", "cpu", "threads", "commit"};
  return columns;
}

std::vector<std::string> to_csv_fields(const Measurement& m) {
  return {std::to_string(m.run_index), m.table, m.scene, m.mesh, std::to_string(m.triangles), std::to_string(m.objects),
          m.backend, m.mode, std::to_string(m.max_depth), std::to_string(m.width), std::to_string(m.height),
          number(m.hash_cell), number(m.octree_depth), number(m.octree_min_objects), number(m.mesh_cell),
          m.hit, std::to_string(m.frames), m.clock, number(m.ms_median), number(m.ms_min), number(m.ms_max),
          number(m.ms_wall_median), number(m.fps), number(m.mrays_per_s), number(m.rays_per_pixel),
          number(m.steps_per_ray), number(m.instance_evals_per_ray), number(m.triangle_evals_per_ray),
          number(m.aabb_tests_per_ray), number(m.triangle_tests_per_ray), number(m.out_of_steps_per_ray),
          number(m.prepare_ms), number(m.build_ms), number(m.structure_bytes), m.check_size, number(m.hit_agreement),
          number(m.id_agreement), number(m.psnr), m.agreement, m.budget_cut ? "1" : "0", m.device, m.driver, m.cpu,
          std::to_string(m.threads), m.commit};
}

std::string configuration_key(const std::vector<std::string>& fields, const std::vector<std::string>& columns) {
  std::string key;
  for (const std::string& name : kKeyColumns)
    for (size_t i = 0; i < columns.size(); ++i)
      if (columns[i] == name) key += fields.at(i) + '|';
  return key;
}

std::string configuration_key(const Measurement& m) { return configuration_key(to_csv_fields(m), measurement_columns()); }

}  // namespace sdfbench
