#pragma once
// The thesis' FPS tables 6.1-6.3 (Menezes 2019, chapter 6; a copy of ../shared/thesis/tables.csv
// is committed as scenes/thesis_tables.csv) and the configuration each table measured.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "renderers/renderer.h"

namespace sdfbench {

struct ThesisTableConfig {
  std::string id;       // "6.1"
  std::string backend;  // ours that reproduces it
  RenderMode mode;      // the thesis removed reflection and refraction only for 6.3
  std::string description;
};

// 6.1: sdf-octree (hash cell 10 + octree, min node size 1), whitted; 6.2: sdf-hash (cell 1),
// whitted; 6.3: tri-aabb, shadow.
const std::vector<ThesisTableConfig>& thesis_table_configs();
const ThesisTableConfig* find_thesis_table(const std::string& id);

struct ThesisValue {
  double fps = 0;
  bool upper_bound = false;  // the thesis wrote "<1" (stored as 1)
};

class ThesisTables {
 public:
  // Throws Error naming the file for a missing file or malformed rows. Lines starting with '#'
  // are comments.
  static ThesisTables load(const std::filesystem::path& path);
  static ThesisTables load_default();  // data_dir()/thesis_tables.csv
  std::optional<ThesisValue> find(const std::string& table, const std::string& mesh, size_t objects) const;
  size_t size() const { return values_.size(); }

 private:
  std::map<std::string, ThesisValue> values_;  // by "table|mesh|objects"
};

}  // namespace sdfbench
