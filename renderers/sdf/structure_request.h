#pragma once
// An optional structure a backend asks for besides the exact ones every SDF backend uses (mesh
// grids and scene hash), made by the backend from its parameters with the function its
// structure's folder declares (sdf-bricks: structure_request(const BrickFieldParams&) in
// brick_field.h; sdf-global: structure_request(const GlobalFieldParams&) in global_field.h).
// build_scene_sdf and obtain_scene_sdf take a list of them and name no structure: the request
// says which cache codec stores its structure, describes and checks its parameters, judges a
// cached copy and builds the structure.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "renderers/sdf/mesh_distance_grid.h"
#include "scenes/scene.h"

namespace sdfbench::sdf {

struct OptionalStructure;
struct SceneSdf;

class StructureRequest {
 public:
  virtual ~StructureRequest() = default;
  // The kind of the cache codec that stores the structure (cache/section_codec.h), which is also
  // its key in SceneSdf::optional.
  virtual uint32_t kind() const = 0;
  // The requested parameters as flags ("--voxels 16 --brick-band 3 --sdf-format f16").
  virtual std::string describe() const = 0;
  // Throws Error for parameters the builder cannot take.
  virtual void validate() const = 0;
  // Why `held` (a cache's structure of this kind) does not serve the request ("built with brick
  // fields --voxels 16 ..., requested --voxels 32 ..."); empty when it does.
  virtual std::string differs(const OptionalStructure& held) const = 0;
  // What of `held` disagrees with what its own parameters give for `scene` (values a build
  // derives, which a cache edited and resealed could change: the checksum is no
  // authentication); empty when nothing does.
  virtual std::string disagrees(const OptionalStructure& held, const Scene& scene) const { return {}; }
  // Adds (or replaces) the structure in `sdf`, sampled from its exact structures (built with
  // `mesh_params`); this process' earlier build of the same one is reused (build_reuse.h).
  virtual void build(SceneSdf& sdf, const Scene& scene, const MeshGridParams& mesh_params) const = 0;
};

using StructureRequests = std::vector<std::shared_ptr<const StructureRequest>>;

}  // namespace sdfbench::sdf
