// Fuzz target for the OBJ loader (the validating pass and tinyobjloader behind it). Every input
// must load as a mesh the renderers can trust (finite positions, every index in range) or be
// refused with sdfbench::Error; anything else (another exception, a crash, a sanitizer report)
// fails. Built and run like the cache target (tests/CMakeLists.txt, fuzz/text_fuzz_driver.cpp).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "scenes/mesh.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const sdfbench::Mesh mesh = sdfbench::parse_obj(text, "fuzz.obj", "fuzz");
    bool ok = !mesh.triangles.empty() && mesh.normals.size() == mesh.positions.size();
    for (const glm::vec3& p : mesh.positions) ok = ok && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
    for (const glm::uvec3& t : mesh.triangles)
      ok = ok && t.x < mesh.positions.size() && t.y < mesh.positions.size() && t.z < mesh.positions.size();
    if (!ok) {
      std::fprintf(stderr, "FAIL: an accepted OBJ gives a mesh with a non-finite position or a bad index\n");
      std::abort();
    }
  } catch (const sdfbench::Error&) {
  }
  return 0;
}
