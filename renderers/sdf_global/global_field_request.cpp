// sdf-global's request for its global field (structure_request.h): what build_scene_sdf and
// obtain_scene_sdf build, and how a cached copy is judged.
#include "renderers/sdf/build_reuse.h"
#include "renderers/sdf/scene_sdf.h"
#include "renderers/sdf_global/global_field.h"

namespace sdfbench::sdf {
namespace {

class GlobalFieldRequest final : public StructureRequest {
 public:
  explicit GlobalFieldRequest(const GlobalFieldParams& params) : params_(params) {}

  uint32_t kind() const override { return GlobalFieldStructure::kKind; }
  std::string describe() const override { return sdf::describe(params_); }
  void validate() const override { sdf::validate(params_); }

  std::string differs(const OptionalStructure& held) const override {
    const GlobalFieldParams& built = dynamic_cast<const GlobalFieldStructure&>(held).params;
    return same(built, params_) ? "" : "built with a global field " + sdf::describe(built) + ", requested " + describe();
  }

  std::string disagrees(const OptionalStructure& held, const Scene& scene) const override {
    const GlobalFieldStructure& global = dynamic_cast<const GlobalFieldStructure&>(held);
    if (scene.instances.empty() || global.field.field.voxel == global_field_voxel(scene, global.params)) return "";
    return "its global field's voxel is not the one its request (" + sdf::describe(global.params) +
           ") gives for this scene (a cache edited and resealed?)";
  }

  void build(SceneSdf& sdf, const Scene& scene, const MeshGridParams& mesh_params) const override {
    const BuildKey key = BuildKey("global field").add(scene).add(mesh_params).add(params_.voxel).add(params_.band)
                             .add(params_.format).add(params_.max_bytes);
    sdf.set(reuse_build(key, [&] { return GlobalFieldStructure(params_, build_global_field(scene, sdf, mesh_params, params_)); }));
  }

 private:
  GlobalFieldParams params_;
};

}  // namespace

std::shared_ptr<const StructureRequest> structure_request(const GlobalFieldParams& params) {
  return std::make_shared<const GlobalFieldRequest>(params);
}

}  // namespace sdfbench::sdf
