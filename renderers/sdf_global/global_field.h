#pragma once
// One sampled distance field over the whole scene (issue 29), as Unreal Engine 5's global
// distance field composites its instances: the brick format of brick_field.h (8^3 samples per
// brick, shared borders, an indirection table, a band, a coarse level at the brick corners), laid
// over the scene's box in world units, its values the distance to the nearest instance. A step
// costs one fetch however many instances the scene has.
//
// Values: min over instances of the unsigned distance (each from the instance's exact mesh grid,
// a lower bound where a point lies outside that grid's box), negative inside any instance. So
// |v| <= u(p), u the distance to the union of the surfaces, and brick_field.h's bound holds:
// |trilinear| - delta - quantization <= u(p). Per stored brick, a list of the instances whose
// surface may come within kListSlackVoxels of the brick: the candidates of an exact hit there.
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "renderers/sdf/scene_sdf.h"
#include "renderers/sdf/structure_request.h"
#include "renderers/sdf_bricks/brick_field.h"
#include "scenes/scene.h"

namespace sdfbench::sdf {

struct GlobalFieldParams {
  float voxel = 0.0f;  // --global-voxel in world units; 0: auto_global_voxel()
  uint32_t band = 4;   // --brick-band
  SdfFormat format = SdfFormat::f32;  // --sdf-format
  // --max-structure-mb: the build stops with an Error when the field would pass this.
  uint64_t max_bytes = kDefaultMaxStructureBytes;
};
inline bool same(const GlobalFieldParams& a, const GlobalFieldParams& b) {
  return a.voxel == b.voxel && a.band == b.band && a.format == b.format;
}
// "--global-voxel 0.25 --brick-band 4 --sdf-format f32" (in global_field_codec.cpp, which the cache
// fuzz target also compiles, so that the codec can name them in messages).
std::string describe(const GlobalFieldParams& params);
void validate(const GlobalFieldParams& params);          // throws Error naming the flag

// --global-voxel auto: the median instance's largest world extent / kAutoVoxelsPerInstance (so a
// typical object spans that many voxels, whatever the scene's units), but never more than
// kMaxGlobalCells cells along the scene's largest extent. Chosen by measurement (docs/backends.md, "sdf-global").
inline constexpr float kAutoVoxelsPerInstance = 10.0f;
inline constexpr uint32_t kMaxGlobalCells = 2048;
float auto_global_voxel(const Scene& scene);

// Instances a stored brick lists: those whose surface may lie within this many voxels of it (the
// exact window test reaches BRICK_BEHIND_VOXELS behind its point and a rounding slack past the
// brick's far face), plus a relative rounding slack of the coordinates.
inline constexpr float kListSlackVoxels = 0.25f;

struct GlobalField {
  BrickField field;                // world space; one field, as a mesh's
  float voxel_request = 0.0f;      // --global-voxel as given (0: auto)
  std::vector<uint32_t> list_begin;      // per stored brick + 1: its instances are list_instances[begin[s] .. begin[s+1])
  std::vector<uint32_t> list_instances;
  double build_ms = 0.0;

  size_t bytes() const { return field.bytes() + (list_begin.size() + list_instances.size()) * sizeof(uint32_t); }
};

// The voxel a build uses: the request, or auto_global_voxel(); never below 1e-6 of the scene's
// extent (a size float can step by). A cache's field is checked against it.
float global_field_voxel(const Scene& scene, const GlobalFieldParams& params);

// Built in parallel (TBB) from `sdf`'s mesh grids (built with `mesh_params`) and its
// world_to_object; where the band reaches beyond a mesh grid's box (which gives only a bound
// there), the samples come from ExactMeshDistance's nearest-triangle query. Progress on stderr for
// long builds. Throws Error for a lattice of more than kMaxHashCells bricks or a field over
// params.max_bytes (naming the flags to change). A scene without mesh instances gets one empty brick.

GlobalField build_global_field(const Scene& scene, const SceneSdf& sdf, const MeshGridParams& mesh_params,
                               const GlobalFieldParams& params);

// sdf-global's optional structure in SceneSdf: the global field built with `params`
// (global_field_request.cpp builds it, global_field_codec.cpp stores it in the cache).
struct GlobalFieldStructure final : OptionalStructure {
  static constexpr uint32_t kKind = 4;  // its cache codec's kind
  GlobalFieldParams params;
  GlobalField field;

  GlobalFieldStructure(const GlobalFieldParams& params, GlobalField field) : params(params), field(std::move(field)) {}
  double build_ms() const override { return field.build_ms; }
  size_t bytes() const override { return field.bytes(); }
};

// The request for the global field with these parameters (structure_request.h): sampled from the
// mesh grids, this process' earlier build for the same geometry reused; a cached field whose
// voxel is not the one its parameters give for the scene disagrees with itself.
std::shared_ptr<const StructureRequest> structure_request(const GlobalFieldParams& params);

}  // namespace sdfbench::sdf
