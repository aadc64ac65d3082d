#include "renderers/vk_rt/acceleration_structures.h"

#include <algorithm>
#include <string>

#include "renderers/vulkan/one_time_commands.h"
#include "renderers/vulkan/vk_error.h"
#include "util/error.h"
#include "util/morton.h"

namespace sdfbench {
namespace {

constexpr VkBufferUsageFlags kAddressable = VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
constexpr uint32_t kMaxCustomIndex = 1u << 24;  // instanceCustomIndex has 24 bits


// Makes acceleration-structure writes (build, copy) visible to what reads them next: a later
// build or copy, or the ray-tracing shaders.
void structure_barrier(VkCommandBuffer cmd, VkPipelineStageFlags dst_stage) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
  barrier.dstAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, dst_stage, 0, 1, &barrier, 0,
                       nullptr, 0, nullptr);
}

}  // namespace

AccelerationStructures::AccelerationStructures(const VulkanContext& context, const RayTracingFunctions& functions,
                                               const Scene& scene, const TriangleBuffers& tables)
    : context_(context), rt_(functions) {
  VkPhysicalDeviceAccelerationStructurePropertiesKHR limits{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  properties.pNext = &limits;
  vkGetPhysicalDeviceProperties2(context.physical_device(), &properties);
  scratch_alignment_ = std::max<VkDeviceSize>(limits.minAccelerationStructureScratchOffsetAlignment, 1);
  const std::string device = "Vulkan device '" + context.info().name + "'";
  if (scene.instances.size() > std::min<uint64_t>(limits.maxInstanceCount, kMaxCustomIndex))
    throw Error("the scene has " + std::to_string(scene.instances.size()) + " instances, more than a top-level "
                "acceleration structure of " + device + " holds (" +
                std::to_string(std::min<uint64_t>(limits.maxInstanceCount, kMaxCustomIndex)) + ")");
  for (const Mesh& mesh : scene.meshes)
    if (mesh.triangle_count() > limits.maxPrimitiveCount)
      throw Error("mesh '" + mesh.name + "' has " + std::to_string(mesh.triangle_count()) +
                  " triangles, more than a bottom-level acceleration structure of " + device + " holds (" +
                  std::to_string(limits.maxPrimitiveCount) + ")");
  try {
    build_bottom_levels(scene, tables);
    build_top_level(scene);
  } catch (...) {
    for (Structure& s : bottom_levels_) destroy(s);
    destroy(top_level_);
    throw;
  }
}

AccelerationStructures::~AccelerationStructures() {
  for (Structure& s : bottom_levels_) destroy(s);
  destroy(top_level_);
}

uint64_t AccelerationStructures::bytes() const {
  uint64_t total = top_level_.storage.size();
  for (const Structure& s : bottom_levels_) total += s.storage.size();
  return total;
}

AccelerationStructures::Structure AccelerationStructures::create(VkAccelerationStructureTypeKHR type, VkDeviceSize bytes,
                                                                 const char* what) const {
  Structure s;
  s.storage = GpuBuffer(context_, bytes, VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR | kAddressable,
                        GpuBuffer::Use::DeviceOnly, what);
  VkAccelerationStructureCreateInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
  info.buffer = s.storage.handle();
  info.size = bytes;
  info.type = type;
  vk_check(rt_.create_acceleration_structure(context_.device(), &info, nullptr, &s.handle),
           "vkCreateAccelerationStructureKHR");
  return s;
}

void AccelerationStructures::destroy(Structure& s) const {
  if (s.handle) rt_.destroy_acceleration_structure(context_.device(), s.handle, nullptr);
  s.handle = VK_NULL_HANDLE;
  s.storage = GpuBuffer();
}

void AccelerationStructures::build_bottom_levels(const Scene& scene, const TriangleBuffers& tables) {
  const VkDeviceAddress vertices = tables.vertices.device_address();
  std::vector<VkAccelerationStructureGeometryKHR> geometries;
  std::vector<uint32_t> triangle_counts;
  mesh_level_.assign(scene.meshes.size(), -1);
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const uint32_t triangles = static_cast<uint32_t>(scene.meshes[m].triangle_count());
    if (triangles == 0) continue;
    // Unindexed: the shared vertex buffer holds 3 vertices (vec4, xyz used) per triangle.
    VkAccelerationStructureGeometryKHR g{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
    g.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
    g.flags = VK_GEOMETRY_OPAQUE_BIT_KHR;
    VkAccelerationStructureGeometryTrianglesDataKHR& t = g.geometry.triangles;
    t.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR;
    t.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
    t.vertexData.deviceAddress = vertices + VkDeviceAddress{tables.first_triangle[m]} * 3 * sizeof(glm::vec4);
    t.vertexStride = sizeof(glm::vec4);
    t.maxVertex = 3 * triangles - 1;
    t.indexType = VK_INDEX_TYPE_NONE_KHR;
    mesh_level_[m] = static_cast<int>(geometries.size());
    geometries.push_back(g);
    triangle_counts.push_back(triangles);
  }
  const size_t count = geometries.size();
  if (count == 0) return;

  // Sizes first, then one build of every bottom level, each in its own scratch region.
  std::vector<VkAccelerationStructureBuildGeometryInfoKHR> builds(count);
  std::vector<Structure> built(count);
  std::vector<VkDeviceSize> scratch_offsets(count);
  VkDeviceSize scratch_bytes = 0;
  try {
    for (size_t i = 0; i < count; ++i) {
      VkAccelerationStructureBuildGeometryInfoKHR& b = builds[i];
      b = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
      b.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
      b.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR |
                VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_COMPACTION_BIT_KHR;
      b.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
      b.geometryCount = 1;
      b.pGeometries = &geometries[i];
      VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
      rt_.get_build_sizes(context_.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &b, &triangle_counts[i],
                          &sizes);
      built[i] = create(VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, sizes.accelerationStructureSize,
                        "bottom-level acceleration structure");
      b.dstAccelerationStructure = built[i].handle;
      scratch_offsets[i] = scratch_bytes;
      scratch_bytes = align_up(scratch_bytes + sizes.buildScratchSize, scratch_alignment_);
    }
    GpuBuffer scratch(context_, scratch_bytes + scratch_alignment_, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | kAddressable,
                      GpuBuffer::Use::DeviceOnly, "acceleration-structure build scratch");
    const VkDeviceAddress scratch_base = align_up(scratch.device_address(), scratch_alignment_);
    std::vector<VkAccelerationStructureBuildRangeInfoKHR> ranges(count);
    std::vector<const VkAccelerationStructureBuildRangeInfoKHR*> range_pointers(count);
    std::vector<VkAccelerationStructureKHR> handles(count);
    for (size_t i = 0; i < count; ++i) {
      builds[i].scratchData.deviceAddress = scratch_base + scratch_offsets[i];
      ranges[i] = {triangle_counts[i], 0, 0, 0};
      range_pointers[i] = &ranges[i];
      handles[i] = built[i].handle;
    }
    VkQueryPoolCreateInfo query_info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    query_info.queryType = VK_QUERY_TYPE_ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR;
    query_info.queryCount = static_cast<uint32_t>(count);
    VkQueryPool queries = VK_NULL_HANDLE;
    vk_check(vkCreateQueryPool(context_.device(), &query_info, nullptr, &queries), "vkCreateQueryPool");
    std::vector<VkDeviceSize> compacted(count);
    try {
      run_one_time_commands(context_, [&](VkCommandBuffer cmd) {
        vkCmdResetQueryPool(cmd, queries, 0, static_cast<uint32_t>(count));
        rt_.cmd_build_acceleration_structures(cmd, static_cast<uint32_t>(count), builds.data(), range_pointers.data());
        structure_barrier(cmd, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR);
        rt_.cmd_write_properties(cmd, static_cast<uint32_t>(count), handles.data(),
                                 VK_QUERY_TYPE_ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR, queries, 0);
      });
      vk_check(vkGetQueryPoolResults(context_.device(), queries, 0, static_cast<uint32_t>(count),
                                     count * sizeof(VkDeviceSize), compacted.data(), sizeof(VkDeviceSize),
                                     VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
               "vkGetQueryPoolResults");
    } catch (...) {
      vkDestroyQueryPool(context_.device(), queries, nullptr);
      throw;
    }
    vkDestroyQueryPool(context_.device(), queries, nullptr);

    // Compaction: a copy into a structure of the size the build reported.
    for (size_t i = 0; i < count; ++i)
      bottom_levels_.push_back(create(VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, compacted[i],
                                      "compacted bottom-level acceleration structure"));
    run_one_time_commands(context_, [&](VkCommandBuffer cmd) {
      for (size_t i = 0; i < count; ++i) {
        VkCopyAccelerationStructureInfoKHR copy{VK_STRUCTURE_TYPE_COPY_ACCELERATION_STRUCTURE_INFO_KHR};
        copy.src = built[i].handle;
        copy.dst = bottom_levels_[i].handle;
        copy.mode = VK_COPY_ACCELERATION_STRUCTURE_MODE_COMPACT_KHR;
        rt_.cmd_copy_acceleration_structure(cmd, &copy);
      }
      structure_barrier(cmd, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR);
    });
  } catch (...) {
    for (Structure& s : built) destroy(s);
    throw;
  }
  for (Structure& s : built) destroy(s);
}

void AccelerationStructures::build_top_level(const Scene& scene) {
  // Instances in Morton order of their centres. lavapipe's builder (Mesa 25.0) halves the
  // primitives in the order given, without sorting them in space: in scene order the top level of
  // 1000 bunnies culled almost nothing (frame time grew linearly with the count). Any builder is
  // free to reorder; the custom index keeps the instance id.
  std::vector<std::pair<uint32_t, uint32_t>> order;  // Morton code, instance
  Aabb all;
  for (const Instance& instance : scene.instances) all.extend(scene.world_bounds(instance));
  for (size_t i = 0; i < scene.instances.size(); ++i)
    if (mesh_level_[scene.instances[i].mesh] >= 0) {  // not a mesh without triangles
      const Aabb b = scene.world_bounds(scene.instances[i]);
      order.emplace_back(morton_code(b.center(), all.min, all.max), static_cast<uint32_t>(i));
    }
  std::sort(order.begin(), order.end());
  std::vector<VkAccelerationStructureInstanceKHR> records;
  for (const auto& [code, i] : order) {
    const Instance& instance = scene.instances[i];
    const int level = mesh_level_[instance.mesh];
    VkAccelerationStructureDeviceAddressInfoKHR address{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
    address.accelerationStructure = bottom_levels_[level].handle;
    VkAccelerationStructureInstanceKHR r{};
    const glm::mat4 m = instance.transform.object_to_world();
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 4; ++col) r.transform.matrix[row][col] = m[col][row];  // row-major 3x4
    r.instanceCustomIndex = i;
    r.mask = 0xff;
    r.instanceShaderBindingTableRecordOffset = 0;
    r.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR;
    r.accelerationStructureReference = rt_.get_acceleration_structure_address(context_.device(), &address);
    records.push_back(r);
  }
  const size_t record_bytes = records.size() * sizeof(VkAccelerationStructureInstanceKHR);
  instances_ = GpuBuffer(context_, record_bytes,
                         VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR | kAddressable,
                         GpuBuffer::Use::Upload, "top-level instance records");
  if (record_bytes) instances_.write(records.data(), record_bytes);

  VkAccelerationStructureGeometryKHR geometry{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geometry.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  geometry.geometry.instances.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR;
  geometry.geometry.instances.arrayOfPointers = VK_FALSE;
  geometry.geometry.instances.data.deviceAddress = instances_.device_address();
  VkAccelerationStructureBuildGeometryInfoKHR build{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  build.type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
  build.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
  build.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  build.geometryCount = 1;
  build.pGeometries = &geometry;
  const uint32_t count = static_cast<uint32_t>(records.size());
  VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  rt_.get_build_sizes(context_.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &build, &count, &sizes);
  top_level_ = create(VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, sizes.accelerationStructureSize,
                      "top-level acceleration structure");
  GpuBuffer scratch(context_, sizes.buildScratchSize + scratch_alignment_, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | kAddressable,
                    GpuBuffer::Use::DeviceOnly, "acceleration-structure build scratch");
  build.dstAccelerationStructure = top_level_.handle;
  build.scratchData.deviceAddress = align_up(scratch.device_address(), scratch_alignment_);
  const VkAccelerationStructureBuildRangeInfoKHR range{count, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
  run_one_time_commands(context_, [&](VkCommandBuffer cmd) {
    rt_.cmd_build_acceleration_structures(cmd, 1, &build, &ranges);
    structure_barrier(cmd, VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR);
  });
}

}  // namespace sdfbench
