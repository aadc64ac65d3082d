// Fuzz target for the scene descriptor loader (JSON, implicit shapes, and the meshes and images
// it names, resolved beside scenes/ so the committed scenes load). Every input must load or be
// refused with sdfbench::Error; anything else (another exception, a crash, a sanitizer report)
// fails. Built and run like the cache target (tests/CMakeLists.txt, fuzz/text_fuzz_driver.cpp).
#include <cstdint>
#include <string>

#include "scenes/mesh.h"
#include "scenes/scene_loader.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::filesystem::path origin = sdfbench::data_dir() / "fuzz.json";
  try {
    sdfbench::parse_scene_json(std::string(reinterpret_cast<const char*>(data), size), origin);
  } catch (const sdfbench::Error&) {
  }
  return 0;
}
