#pragma once
#include <memory>

#include "renderers/renderer.h"
#include "renderers/vulkan/triangle_buffers.h"
#include "renderers/vulkan/vulkan_context.h"
#include "renderers/vulkan/vulkan_frame_runner.h"

namespace sdfbench {

// Vulkan compute, per-instance AABB then every triangle (thesis table 6.3).
struct BackendInfo;
BackendInfo tri_aabb_backend();  // its entry in renderers/backend_registry.h

class TriAabbRenderer : public Renderer {
 public:
  explicit TriAabbRenderer(const BackendOptions& options);
  std::string name() const override { return "tri-aabb"; }
  std::string device_name() const override { return context_.info().name; }
  std::string driver_name() const override { return context_.info().driver + " " + context_.info().driver_info; }
  void prepare(const Scene& scene) override;
  FrameResult render(const FrameRequest& request) override { return runner_.run(request); }
  uint32_t validation_messages() const override { return context_.validation_messages(); }

 private:
  VulkanContext context_;
  std::unique_ptr<TriangleBuffers> tables_;
  VulkanFrameRunner runner_;  // declared last: destroyed first, before the buffers it binds
};

}  // namespace sdfbench
