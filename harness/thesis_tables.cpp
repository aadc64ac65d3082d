#include "harness/thesis_tables.h"

#include <charconv>
#include <sstream>

#include "harness/csv.h"
#include "scenes/mesh.h"
#include "util/error.h"
#include "util/input_file.h"

namespace sdfbench {
namespace {

std::string key(const std::string& table, const std::string& mesh, size_t objects) {
  return table + "|" + mesh + "|" + std::to_string(objects);
}

template <class T>
T parse_number(const std::string& text, const std::string& where) {
  T value{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size())
    throw Error(where + ": '" + text + "' is not a number");
  return value;
}

}  // namespace

const std::vector<ThesisTableConfig>& thesis_table_configs() {
  static const std::vector<ThesisTableConfig> configs = {
      {"6.1", "sdf-octree", RenderMode::Whitted, "SDF, hash cell 10 + octree (min node size 1), with reflection and refraction"},
      {"6.2", "sdf-hash", RenderMode::Whitted, "SDF, hash cell 1, no octree, with reflection and refraction"},
      {"6.3", "tri-aabb", RenderMode::Shadow, "triangles with a per-object AABB test, reflection and refraction removed"},
  };
  return configs;
}

const ThesisTableConfig* find_thesis_table(const std::string& id) {
  for (const ThesisTableConfig& c : thesis_table_configs())
    if (c.id == id) return &c;
  return nullptr;
}

ThesisTables ThesisTables::load(const std::filesystem::path& path) {
  std::istringstream in(read_input_file(path, "thesis tables", 1 << 20));  // the committed one is ~2 KB
  std::string line, text;
  while (std::getline(in, line))
    if (line.rfind('#', 0) != 0) text += line + '\n';
  const CsvTable csv = parse_csv(text, path.string());
  const size_t table = csv.column("table"), mesh = csv.column("mesh"), objects = csv.column("objects"),
               fps = csv.column("fps"), bound = csv.column("fps_upper_bound");
  ThesisTables tables;
  for (size_t r = 0; r < csv.rows.size(); ++r) {
    const auto& row = csv.rows[r];
    const std::string where = path.string() + " row " + std::to_string(r + 1);
    const ThesisValue value{parse_number<double>(row[fps], where), row[bound] == "1"};
    tables.values_[key(row[table], row[mesh], parse_number<size_t>(row[objects], where))] = value;
  }
  return tables;
}

ThesisTables ThesisTables::load_default() { return load(data_dir() / "thesis_tables.csv"); }

std::optional<ThesisValue> ThesisTables::find(const std::string& table, const std::string& mesh, size_t objects) const {
  const auto it = values_.find(key(table, mesh, objects));
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

}  // namespace sdfbench
