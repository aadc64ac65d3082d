// sdf-bricks' request for its brick fields (structure_request.h): what build_scene_sdf and
// obtain_scene_sdf build, and how a cached copy is judged.
#include "renderers/sdf/build_reuse.h"
#include "renderers/sdf/scene_sdf.h"
#include "renderers/sdf_bricks/brick_field.h"

namespace sdfbench::sdf {
namespace {

class BrickFieldsRequest final : public StructureRequest {
 public:
  explicit BrickFieldsRequest(const BrickFieldParams& params) : params_(params) {}

  uint32_t kind() const override { return BrickFields::kKind; }
  std::string describe() const override { return sdf::describe(params_); }
  void validate() const override { sdf::validate(params_); }

  std::string differs(const OptionalStructure& held) const override {
    const BrickFieldParams& built = dynamic_cast<const BrickFields&>(held).params;
    return same(built, params_) ? "" : "built with brick fields " + sdf::describe(built) + ", requested " + describe();
  }

  void build(SceneSdf& sdf, const Scene& scene, const MeshGridParams& mesh_params) const override {
    std::vector<BrickField> fields;
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
      // Keyed by the mesh (not the scene): scenes of the same meshes share their fields.
      const BuildKey key = BuildKey("brick field").add(scene.meshes[m]).add(mesh_params).add(params_.voxels).add(params_.band)
                               .add(params_.format).add(params_.max_bytes);
      fields.push_back(*reuse_build(key, [&] { return build_brick_field(scene.meshes[m], sdf.mesh_grids[m], params_); }));
    }
    sdf.set(BrickFields(params_, std::move(fields)));
  }

 private:
  BrickFieldParams params_;
};

}  // namespace

std::shared_ptr<const StructureRequest> structure_request(const BrickFieldParams& params) {
  return std::make_shared<const BrickFieldsRequest>(params);
}

}  // namespace sdfbench::sdf
