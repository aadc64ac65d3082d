#pragma once
#include <memory>

#include "renderers/renderer.h"
#include "renderers/sdf/scene_hash.h"
#include "renderers/sdf/sphere_tracer.h"

namespace sdfbench {

// The CPU reference for the SDF backends: the scene hash (+ octree) and mesh distance grids,
// sphere-traced on the CPU with the GPU's parameters. Slow; for checking the structures.
class SdfCpuRenderer : public Renderer {
 public:
  explicit SdfCpuRenderer(const BackendOptions& options);
  std::string name() const override { return "sdf-cpu"; }
  std::string device_name() const override;
  std::string driver_name() const override { return "sdfbench CPU sphere tracer"; }
  void prepare(const Scene& scene) override;
  FrameResult render(const FrameRequest& request) override;
  const sdf::SceneSdf& structures() const { return *sdf_; }
  std::optional<StructureStats> structure_stats() const override;

 private:
  BackendOptions options_;
  unsigned threads_;
  const Scene* scene_ = nullptr;
  std::unique_ptr<sdf::SceneSdf> sdf_;
  std::unique_ptr<sdf::SphereTracer> tracer_;
};

// Its entry in the backend registry (renderers/backend_registry.h).
struct BackendInfo;
BackendInfo sdf_cpu_backend();

}  // namespace sdfbench
