#include "scenes/mesh_cache_dir.h"

#include <cstdlib>

namespace sdfbench {

std::filesystem::path mesh_cache_dir() {
  if (const char* env = std::getenv("SDFBENCH_MESH_CACHE"); env && *env) return env;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "sdfbench" / "meshes";
  if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "sdfbench" / "meshes";
  return {};
}

}  // namespace sdfbench
