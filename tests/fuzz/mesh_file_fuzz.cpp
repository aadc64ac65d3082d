// Fuzz target for the PLY, OFF and glTF readers (scenes/mesh_file.*: the header checks and
// assimp behind them), one binary per format (SDFBENCH_MESH_FORMAT: "ply", "off", "gltf" or
// "glb"). Every input must load as a mesh the renderers can trust (finite positions, every index
// in range, at least one triangle) or be refused with sdfbench::Error; anything else (another
// exception, a crash, a sanitizer report, a hang past ctest's timeout) fails. Built and run
// like the OBJ target (tests/CMakeLists.txt, fuzz/text_fuzz_driver.cpp).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>

#include "scenes/mesh_file.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const sdfbench::Mesh mesh = sdfbench::parse_mesh_bytes(
        std::span<const std::byte>(reinterpret_cast<const std::byte*>(data), size), SDFBENCH_MESH_FORMAT,
        "fuzz." SDFBENCH_MESH_FORMAT, "fuzz");
    bool ok = !mesh.triangles.empty() && mesh.normals.size() == mesh.positions.size();
    for (const glm::vec3& p : mesh.positions) ok = ok && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
    for (const glm::uvec3& t : mesh.triangles)
      ok = ok && t.x < mesh.positions.size() && t.y < mesh.positions.size() && t.z < mesh.positions.size();
    if (!ok) {
      std::fprintf(stderr, "FAIL: an accepted " SDFBENCH_MESH_FORMAT " file gives a mesh with a bad position or index\n");
      std::abort();
    }
  } catch (const sdfbench::Error&) {
  }
  return 0;
}
