#include "renderers/sdf_bricks/brick_field.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include <glm/gtc/packing.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "util/error.h"
#include "util/input_file.h"
#include "util/progress.h"

namespace sdfbench::sdf {
namespace {

size_t index_of(const glm::uvec3& c, const glm::uvec3& dims) { return c.x + size_t(dims.x) * (c.y + size_t(dims.y) * c.z); }
glm::uvec3 coords_of(size_t i, const glm::uvec3& dims) {
  return glm::uvec3(i % dims.x, (i / dims.x) % dims.y, i / (size_t(dims.x) * dims.y));
}

}  // namespace

void store_sample(SdfFormat format, float band, float value, uint8_t* out) {
  const float v = std::clamp(value, -band, band);
  switch (format) {
    case SdfFormat::f32: std::memcpy(out, &v, 4); return;
    case SdfFormat::f16: {
      const uint16_t h = glm::packHalf1x16(v);
      std::memcpy(out, &h, 2);
      return;
    }
    case SdfFormat::u8: *out = static_cast<uint8_t>(std::lround((v / band + 1.0f) * 127.5f)); return;
  }
}

void validate(const BrickFieldParams& params) {
  // The builder's domain, for a record made in code (tests). The flags' ranges are their
  // declarations' (sdf_bricks_renderer.cpp, whose --voxels is up to kMaxVoxels, and
  // brick_field_tables.cpp; checked where a value is parsed), and a cache file's values are checked
  // where they are decoded (brick_field_codec.cpp).
  if (params.voxels < 4 || params.voxels > kMaxVoxels || params.band < 1 || params.band > 16)
    throw InternalError("a brick field of " + std::to_string(params.voxels) + " voxels and band " +
                        std::to_string(params.band) + " (voxels from 4 to " + std::to_string(kMaxVoxels) +
                        ", band from 1 to 16 voxels)");
}


BrickField build_brick_field(const Mesh& mesh, const MeshDistanceGrid& given_grid,
                             const BrickFieldParams& params) {
  validate(params);
  const auto start = std::chrono::steady_clock::now();
  BrickField field;
  const glm::vec3 extent = mesh.bounds.max - mesh.bounds.min;
  const float largest = std::max({extent.x, extent.y, extent.z});
  const float scale = std::max({std::abs(mesh.bounds.min.x), std::abs(mesh.bounds.min.y), std::abs(mesh.bounds.min.z),
                                std::abs(mesh.bounds.max.x), std::abs(mesh.bounds.max.y), std::abs(mesh.bounds.max.z)});
  // A flat or point-like mesh still gets voxels of a size float can step by.
  field.voxel = std::max(largest, 1e-5f * scale + 1e-30f) / static_cast<float>(params.voxels);
  field.format = params.format;
  field.band = static_cast<float>(params.band) * field.voxel;
  field.quantization = brick_quantization(params.format, field.band);
  // The lattice covers the mesh and one voxel beyond the band on every side.
  const float margin = static_cast<float>(params.band + 1) * field.voxel;
  field.origin = mesh.bounds.min - margin;
  const glm::vec3 cells = glm::ceil((extent + 2.0f * margin) / field.voxel);
  field.bricks = glm::uvec3(glm::ceil(cells / float(kBrickCells)));
  const size_t brick_count = size_t(field.bricks.x) * field.bricks.y * field.bricks.z;
  const glm::uvec3 corners = field.coarse_dims();
  const float brick_size = float(kBrickCells) * field.voxel;

  // Exact samples everywhere on the lattice: outside its box the mesh grid gives only a bound, so
  // the exact query answers there.
  const ExactMeshDistance exact(given_grid, mesh);

  // Coarse level: the exact signed distance at each brick corner (unclamped).
  field.coarse.resize(size_t(corners.x) * corners.y * corners.z);
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, corners.z), [&](const tbb::blocked_range<uint32_t>& r) {
    for (uint32_t z = r.begin(); z != r.end(); ++z)
      for (uint32_t y = 0; y < corners.y; ++y)
        for (uint32_t x = 0; x < corners.x; ++x)
          field.coarse[index_of({x, y, z}, corners)] =
              exact.signed_distance(field.origin + brick_size * glm::vec3(x, y, z));
  });

  // A brick is stored unless its centre is so far from the surface that no point of it comes
  // within the band: then u >= band on all of it (u is 1-Lipschitz), what the tracers step by.
  const float reach = 0.5f * brick_size * std::sqrt(3.0f);
  std::vector<uint8_t> stored(brick_count, 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, brick_count), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t b = r.begin(); b != r.end(); ++b) {
      const glm::uvec3 c = coords_of(b, field.bricks);
      const glm::vec3 centre = field.origin + brick_size * (glm::vec3(c) + 0.5f);
      stored[b] = exact.distance(centre, reach + field.band) - reach < field.band;  // farther: +inf
    }
  });
  field.indirection.assign(brick_count, kEmptyBrick);
  uint32_t next = 0;
  for (size_t b = 0; b < brick_count; ++b)
    if (stored[b]) field.indirection[b] = next++;
  const size_t sample_bytes = bytes_per_sample(params.format);
  const uint64_t atlas_bytes = uint64_t(next) * kBrickSamples * sample_bytes;
  if (atlas_bytes > params.max_bytes)
    throw Error("the brick field of '" + mesh.name + "' would need " + describe_bytes(atlas_bytes) +
                " (" + std::to_string(next) + " bricks at --voxels " + std::to_string(params.voxels) +
                "), more than --max-structure-mb allows; use fewer --voxels or a smaller --brick-band");
  field.atlas.resize(atlas_bytes);

  ProgressMeter progress("brick field '" + mesh.name + "' (" + std::to_string(next) + " bricks)", brick_count, "bricks");
  tbb::parallel_for(tbb::blocked_range<size_t>(0, brick_count), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t b = r.begin(); b != r.end(); ++b) {
      if (field.indirection[b] == kEmptyBrick) continue;
      const glm::uvec3 c = coords_of(b, field.bricks);
      uint8_t* out = &field.atlas[size_t(field.indirection[b]) * kBrickSamples * sample_bytes];
      for (uint32_t z = 0; z < kBrickSide; ++z)
        for (uint32_t y = 0; y < kBrickSide; ++y)
          for (uint32_t x = 0; x < kBrickSide; ++x, out += sample_bytes) {
            const glm::vec3 p = field.origin + field.voxel * glm::vec3(c * kBrickCells + glm::uvec3(x, y, z));
            store_sample(params.format, field.band, exact.signed_distance(p, field.band), out);  // clamped: no farther
          }
    }
    progress.advance(r.size());
  });
  field.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return field;
}

}  // namespace sdfbench::sdf
