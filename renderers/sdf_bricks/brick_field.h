#pragma once
// A per-mesh sampled distance field as Unreal Engine 5's mesh distance fields store it (issue 28):
// sparse bricks of 8^3 samples (7^3 cells plus a border sample shared with the neighbour, so a
// trilinear lookup never crosses a brick), an indirection table with one entry per brick
// ("empty" outside a narrow band), and a coarse level (one sample per brick corner) for empty
// space. Values are sdfbench's exact signed mesh distance (mesh_distance_grid.h) at the lattice
// points, clamped to the band and stored as f32, f16 or u8.
//
// What a sample gives is a *lower bound* on the distance to the mesh, never an estimate that may
// overshoot: for stored values v_i with |v_i| <= u(c_i) (u the unsigned distance; clamping and
// the exact grid's far-cell bounds keep that), |trilinear(v)(p)| <= u(p) + delta(p) with
// delta(p) = h sqrt(sum over axes f(1 - f)) <= h sqrt(3)/2 (f: p's fractions in its cell; Jensen
// on sum w_i |c_i - p|), and quantization adds at most `quantization` per value. So
// |trilinear| - delta - quantization <= u(p), for any mesh, open or closed; in an empty brick
// u >= band everywhere. The tracers step by that bound and find hits exactly (exact_hit.h), or,
// with --hit field, take the field's own zero crossing.
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/packing.hpp>

#include "renderers/sdf/mesh_distance_grid.h"
#include "renderers/sdf/scene_sdf.h"
#include "renderers/sdf/structure_request.h"
#include "scenes/mesh.h"

namespace sdfbench::sdf {

enum class SdfFormat { f32, f16, u8 };
inline std::string to_string(SdfFormat format) {
  switch (format) {
    case SdfFormat::f32: return "f32";
    case SdfFormat::f16: return "f16";
    case SdfFormat::u8: return "u8";
  }
  return "?";
}
inline size_t bytes_per_sample(SdfFormat format) { return format == SdfFormat::f32 ? 4 : format == SdfFormat::f16 ? 2 : 1; }
// The most a stored value differs from the clamped exact one, with the kernels' arithmetic
// rounding on values up to the band (a few ulps) counted in: f16 has an 11-bit significand, u8
// steps of 2 band / 255.
inline float brick_quantization(SdfFormat format, float band) {
  constexpr float kArithmeticSlack = 4e-6f;
  switch (format) {
    case SdfFormat::f32: return band * kArithmeticSlack;
    case SdfFormat::f16: return band * (1.0f / 2048.0f + kArithmeticSlack);
    case SdfFormat::u8: return band * (1.0f / 255.0f + kArithmeticSlack);
  }
  return band;
}

struct BrickFieldParams {
  uint32_t voxels = 128;  // --voxels: lattice cells along the mesh's largest extent
  uint32_t band = 4;     // --brick-band: bricks within this many voxels of the surface are stored
  SdfFormat format = SdfFormat::f32;  // --sdf-format
  // --max-structure-mb: the build stops with an Error when the atlas would pass this. Not a
  // parameter of the result.
  uint64_t max_bytes = kDefaultMaxStructureBytes;
};
// Whether two fields are built alike (max_bytes decides only whether a build is allowed).
inline bool same(const BrickFieldParams& a, const BrickFieldParams& b) {
  return a.voxels == b.voxels && a.band == b.band && a.format == b.format;
}
// "--voxels 128 --brick-band 4 --sdf-format f32" (inline: the cache codec, also compiled alone
// into the cache fuzz target, names them in messages).
inline std::string describe(const BrickFieldParams& params) {
  return "--voxels " + std::to_string(params.voxels) + " --brick-band " + std::to_string(params.band) + " --sdf-format " +
         to_string(params.format);
}

inline constexpr uint32_t kBrickCells = 7;    // unique cells per brick and axis
inline constexpr uint32_t kBrickSide = 8;     // samples per brick and axis (the border shared)
inline constexpr uint32_t kBrickSamples = kBrickSide * kBrickSide * kBrickSide;
inline constexpr uint32_t kEmptyBrick = UINT32_MAX;
inline constexpr uint32_t kMaxVoxels = 1024;

struct BrickField {
  glm::vec3 origin{0.0f};  // lattice point (0, 0, 0); point (i, j, k) at origin + voxel * (i, j, k)
  float voxel = 0.0f;      // lattice spacing h, mesh units
  glm::uvec3 bricks{0u};   // bricks per axis; the lattice has kBrickCells * bricks + 1 points per axis
  SdfFormat format = SdfFormat::f32;
  float band = 0.0f;        // band x voxel: stored values are clamped to [-band, band]
  float quantization = 0.0f;  // the most a stored value differs from the clamped exact one
  std::vector<uint32_t> indirection;  // per brick (x fastest): its index in the atlas, or kEmptyBrick
  std::vector<uint8_t> atlas;         // kBrickSamples per stored brick, x fastest, in `format`
  std::vector<float> coarse;          // exact signed distance at each brick corner, (bricks + 1)^3, x fastest;
                                      // with coarse_at_centres one per brick: a lower bound at its centre
  bool coarse_at_centres = false;     // sdf-global's field (global_field.h): an empty brick's bound is one fetch
  double build_ms = 0;

  size_t brick_count() const { return indirection.size(); }
  size_t stored_bricks() const { return atlas.size() / (kBrickSamples * bytes_per_sample(format)); }
  glm::uvec3 coarse_dims() const { return coarse_at_centres ? bricks : bricks + 1u; }
  glm::vec3 box_max() const { return origin + voxel * glm::vec3(bricks * kBrickCells); }
  // Indirection, atlas and coarse level (inline: the cache fuzz target, which compiles no builder,
  // holds fields too).
  size_t bytes() const { return indirection.size() * sizeof(uint32_t) + atlas.size() + coarse.size() * sizeof(float); }
};

// Throws Error for voxels outside 4..kMaxVoxels or band outside 1..16. Built in parallel
// (TBB); the result does not depend on the thread count.
// `grid` is the mesh's exact grid; where the lattice reaches beyond its box (where the grid gives
// only a bound), the samples come from ExactMeshDistance's nearest-triangle query.
void validate(const BrickFieldParams& params);
BrickField build_brick_field(const Mesh& mesh, const MeshDistanceGrid& grid,
                             const BrickFieldParams& params);

// sdf-bricks' optional structure in SceneSdf: a brick field per mesh, built with `params`
// (brick_field_request.cpp builds it, brick_field_codec.cpp stores it in the cache).
struct BrickFields final : OptionalStructure {
  static constexpr uint32_t kKind = 3;  // its cache codec's kind
  BrickFieldParams params;
  std::vector<BrickField> fields;  // per mesh

  BrickFields(const BrickFieldParams& params, std::vector<BrickField> fields) : params(params), fields(std::move(fields)) {}
  double build_ms() const override {
    double ms = 0.0;
    for (const BrickField& f : fields) ms += f.build_ms;
    return ms;
  }
  size_t bytes() const override {
    size_t total = 0;
    for (const BrickField& f : fields) total += f.bytes();
    return total;
  }
};

// The request for brick fields with these parameters (structure_request.h): each mesh's field
// sampled from its grid, this process' earlier build of the same mesh reused.
std::shared_ptr<const StructureRequest> structure_request(const BrickFieldParams& params);

// Writes `value`, clamped to [-band, band], as one sample in `format` (u8: a band-relative UNORM).
void store_sample(SdfFormat format, float band, float value, uint8_t* out);

// Sample `index` of an atlas in `format` as the kernels' texel fetch returns it: f32, f16 ->
// float exactly, u8 as UNORM q / 255. Header-only, like atlas_value: the cache decoder (and its
// fuzz target) checks values with it.
inline float atlas_texel(const std::vector<uint8_t>& atlas, SdfFormat format, size_t index) {
  switch (format) {
    case SdfFormat::f32: {
      float v;
      std::memcpy(&v, &atlas[4 * index], 4);
      return v;
    }
    case SdfFormat::f16: {
      uint16_t h;
      std::memcpy(&h, &atlas[2 * index], 2);
      return glm::unpackHalf1x16(h);
    }
    case SdfFormat::u8: return float(atlas[index]) / 255.0f;
  }
  return 0.0f;
}

// The stored sample `index` of the atlas in mesh units (u8's UNORM mapped to [-band, band]).
inline float atlas_value(const BrickField& field, size_t index) {
  const float texel = atlas_texel(field.atlas, field.format, index);
  return field.format == SdfFormat::u8 ? (texel * 2.0f - 1.0f) * field.band : texel;
}

}  // namespace sdfbench::sdf
