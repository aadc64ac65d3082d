#include "renderers/sdf/scene_sdf.h"

#include "renderers/sdf/build_reuse.h"

namespace sdfbench::sdf {

double build_ms(const SceneSdf& sdf) {
  double ms = sdf.hash.build_ms;
  for (const MeshDistanceGrid& g : sdf.mesh_grids) ms += g.build_ms;
  for (const auto& [kind, structure] : sdf.optional) ms += structure->build_ms();
  return ms;
}

size_t bytes(const SceneSdf& sdf) {
  size_t total = sdf.hash.bytes();
  for (const MeshDistanceGrid& g : sdf.mesh_grids) total += g.bytes();
  for (const auto& [kind, structure] : sdf.optional) total += structure->bytes();
  return total;
}

SceneSdf build_scene_sdf(const Scene& scene, const MeshGridParams& mesh_params, const SceneHashParams& hash_params,
                         const StructureRequests& extras) {
  scene_hash_dims(scene, hash_params);  // an impossible hash is refused before the mesh grids are built
  for (const auto& extra : extras) extra->validate();
  SceneSdf sdf;
  for (const Mesh& mesh : scene.meshes)
    sdf.mesh_grids.push_back(reuse_mesh_grid(mesh, mesh_params, [&] { return build_mesh_distance_grid(mesh, mesh_params); }));
  sdf.hash = reuse_scene_hash(scene, mesh_params, hash_params, [&] { return build_scene_hash(scene, sdf.mesh_grids, hash_params); });
  for (const Instance& instance : scene.instances) sdf.world_to_object.push_back(instance.transform.world_to_object());
  for (const auto& extra : extras) extra->build(sdf, scene, mesh_params);
  return sdf;
}

}  // namespace sdfbench::sdf
