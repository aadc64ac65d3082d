// The built-in backends, in the order help, tables and reports list them. A static library drops
// self-registering objects nobody references, so the built-in declarations are listed here
// (pbrt's way): a new backend adds its declaration function to both lists below, and nothing of it
// is included (each function is defined in the backend's own folder, renderers/<backend>/).
#include <vector>

#include "renderers/backend.h"

namespace sdfbench {

BackendInfo embree_backend();
BackendInfo tri_aabb_backend();
BackendInfo bvh_backend();
BackendInfo vk_rt_backend();
BackendInfo sdf_hash_backend();
BackendInfo sdf_octree_backend();
BackendInfo sdf_bricks_backend();
BackendInfo sdf_global_backend();
BackendInfo sdf_cpu_backend();

std::vector<BackendInfo> builtin_backends() {
  return {embree_backend(),     tri_aabb_backend(),   bvh_backend(),        vk_rt_backend(), sdf_hash_backend(),
          sdf_octree_backend(), sdf_bricks_backend(), sdf_global_backend(), sdf_cpu_backend()};
}

}  // namespace sdfbench
