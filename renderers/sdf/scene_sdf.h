#pragma once
// One scene's SDF: the exact structures every SDF backend uses (a distance grid per mesh, shared
// by its instances, and the scene hash) and the optional structures a backend asked for
// (structure_request.h: sdf-bricks' brick fields, sdf-global's global field), each an entry
// this code knows only through OptionalStructure, keyed by the kind of the cache codec that
// stores it (cache/section_codec.h). A structure's own folder defines its entry type; nothing
// here names one.
#include <cstddef>
#include <cstdint>
#include <concepts>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderers/sdf/mesh_distance_grid.h"
#include "renderers/sdf/scene_hash.h"
#include "renderers/sdf/structure_request.h"
#include "scenes/scene.h"
#include "util/error.h"

namespace sdfbench::sdf {

// An optional structure as SceneSdf holds it. A type derived from it names its codec's kind as
// `static constexpr uint32_t kKind` (SceneSdf::find, set).
struct OptionalStructure {
  virtual ~OptionalStructure() = default;
  virtual double build_ms() const = 0;  // as built (a loaded or reused one keeps its build's time)
  virtual size_t bytes() const = 0;     // payload bytes
};

struct SceneSdf {
  std::vector<MeshDistanceGrid> mesh_grids;
  SceneHash hash;
  std::vector<glm::mat4> world_to_object;  // per instance (build_scene_sdf fills it): queries reuse it
  // The optional structures held, by their codec's kind, at most one of each. Immutable once
  // set: copies of a SceneSdf (and this process' build reuse, build_reuse.h) share them.
  std::map<uint32_t, std::shared_ptr<const OptionalStructure>> optional;

  bool holds(uint32_t kind) const { return optional.count(kind) != 0; }
  // The entry of T's kind, or null.
  template <class T>
  const T* find() const {
    const auto it = optional.find(T::kKind);
    return it == optional.end() ? nullptr : dynamic_cast<const T*>(it->second.get());
  }
  // The entry of T's kind, which the caller asked for (InternalError when it is not held).
  template <class T>
  const T& get() const {
    if (const T* held = find<T>()) return *held;
    throw InternalError("an SDF structure of kind " + std::to_string(T::kKind) + " was read but not built");
  }
  // Adds or replaces the entry of T's kind.
  template <class T>
  const T& set(std::shared_ptr<const T> structure) {
    const T& held = *structure;
    optional[T::kKind] = std::move(structure);
    return held;
  }
  template <class T>
    requires std::derived_from<T, OptionalStructure>
  const T& set(T structure) {
    return set(std::make_shared<const T>(std::move(structure)));
  }
};

// Build time and payload bytes of all of a scene's structures (mesh grids, hash and every
// optional structure held).
double build_ms(const SceneSdf& sdf);
size_t bytes(const SceneSdf& sdf);

// `extras`: the optional structures asked for besides the exact ones (structure_request.h),
// each built by its request from the exact ones.
SceneSdf build_scene_sdf(const Scene& scene, const MeshGridParams& mesh_params, const SceneHashParams& hash_params,
                         const StructureRequests& extras = {});

}  // namespace sdfbench::sdf
