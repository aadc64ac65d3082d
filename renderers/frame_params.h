#pragma once
// Turns a Scene and a frame request into the buffers the shading program reads.
#include <vector>

#include "renderers/renderer.h"
#include "renderers/shading/gpu_types.h"
#include "scenes/scene.h"

namespace sdfbench {

struct ShadingInputs {
  shading::FrameParams frame;
  std::vector<shading::GpuMaterial> materials;
  std::vector<shading::GpuLight> lights;  // never empty (a zero light is padded; frame counts real ones)
  std::vector<shading::GpuImplicitObject> implicit_objects;  // frame.limits.y of them
  std::vector<shading::GpuImplicitNode> implicit_nodes;
};

ShadingInputs make_shading_inputs(const Scene& scene, const FrameRequest& request);

// Scale of the scene as the camera sees it: the diagonal of the box around the camera and the
// objects within reach of its rays (a far outlier does not count; details in the .cpp). The one
// place scale-derived limits come from: the max ray distance (100 x), the implicit objects' and
// --hit thesis's hit epsilons.
float scene_scale(const Scene& scene);

}  // namespace sdfbench
