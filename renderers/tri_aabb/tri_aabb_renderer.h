#pragma once
#include <memory>

#include "renderers/renderer.h"
#include "renderers/vulkan/triangle_buffers.h"
#include "renderers/vulkan/vulkan_frame_runner.h"
#include "renderers/vulkan/vulkan_renderer.h"

namespace sdfbench {

// Vulkan compute, per-instance AABB then every triangle (thesis table 6.3).
class TriAabbRenderer : public VulkanRenderer {
 public:
  explicit TriAabbRenderer(const BackendOptions& options);
  std::string name() const override { return "tri-aabb"; }
  void prepare(const Scene& scene) override;
  FrameResult render(const FrameRequest& request) override { return runner_.run(request); }

 private:
  std::unique_ptr<TriangleBuffers> tables_;
  VulkanFrameRunner runner_;  // declared last: destroyed first, before the buffers it binds
};

// Its entry in the backend registry (renderers/backend_registry.h).
struct BackendInfo;
BackendInfo tri_aabb_backend();

}  // namespace sdfbench
