#pragma once
// What every backend on the Vulkan device shares: its context (the device of --device, with the
// validation layer under --validate), constructed before the derived class's members so that
// their buffers and kernels can use it and are destroyed before it.
#include <string>

#include "renderers/renderer.h"
#include "renderers/vulkan/vulkan_context.h"

namespace sdfbench {

class VulkanRenderer : public Renderer {
 public:
  std::string device_name() const override { return context_.info().name; }
  std::string driver_name() const override { return context_.info().driver + " " + context_.info().driver_info; }
  uint32_t validation_messages() const override { return context_.validation_messages(); }

 protected:
  explicit VulkanRenderer(const BackendOptions& options)
      : context_(VulkanContext::Options{options.device, options.validation}) {}
  VulkanContext context_;
};

}  // namespace sdfbench
