#include "scenes/scene_source.h"

#include "scenes/atrium_scene.h"
#include "scenes/gltf_scene.h"
#include "scenes/mesh_file.h"
#include "scenes/overlap_layout.h"
#include "scenes/scene_loader.h"
#include "scenes/thesis_layout.h"

namespace sdfbench {

Scene load_scene(const std::string& spec) {
  if (spec.rfind("thesis:", 0) == 0) return make_thesis_scene(parse_thesis_spec(spec));
  if (spec.rfind("overlap:", 0) == 0) return make_overlap_scene(parse_overlap_spec(spec));
  if (spec == "atrium" || spec.rfind("atrium:", 0) == 0) return make_atrium_scene(parse_atrium_spec(spec));
  const std::string format = mesh_file_format(spec);
  if (format == "gltf" || format == "glb") return load_gltf_scene(spec);
  return load_scene_file(spec);
}

}  // namespace sdfbench
