#include "renderers/bvh/bvh_renderer.h"

#include <algorithm>
#include <chrono>
#include <limits>

#include "renderers/backend.h"
#include "renderers/bvh/bvh_quality.h"
#include "util/error.h"

namespace sdfbench {
namespace {

GpuBuffer texel_table(const VulkanContext& context, const std::vector<glm::uvec4>& texels, const char* what) {
  const std::vector<glm::uvec4> one(1, glm::uvec4(0));  // a table the kernel never reads still binds a texel
  const std::vector<glm::uvec4>& data = texels.empty() ? one : texels;
  GpuBuffer buffer(context, data.size() * sizeof(glm::uvec4), VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, GpuBuffer::Use::Upload,
                   what);
  buffer.write(data.data(), data.size() * sizeof(glm::uvec4));
  buffer.texel_view(VK_FORMAT_R32G32B32A32_UINT, sizeof(glm::uvec4));
  return buffer;
}

uint32_t saturated(uint64_t v) { return static_cast<uint32_t>(std::min<uint64_t>(v, std::numeric_limits<uint32_t>::max())); }

BvhTop top_of(const std::string& text) {
  return text == "flat" ? BvhTop::Flat : text == "rebraided" ? BvhTop::Rebraided : BvhTop::Instanced;
}

}  // namespace

BvhRenderer::BvhRenderer(const BackendOptions& options)
    : VulkanRenderer(options),
      kernels_(compute_tile_kernels(context_, "bvh.comp")),
      runner_(
          context_,
          [this](const std::string& defines, const std::vector<KernelBinding>& bindings) {
            std::string layout = "#define BVH_WIDTH " + std::to_string(params_.width) + "\n#define BVH_QUANTISED " +
                                 (nodes_ == BvhNodes::Quantised ? "1" : "0") + "\n#define BVH_FLAT " +
                                 (params_.top == BvhTop::Flat ? "1" : "0") + "\n#define BVH_STACK_SIZE " +
                                 std::to_string(stack_size_) + "\n";
            if (visit_limit_ > 0) layout += "#define BVH_VISIT_LIMIT " + std::to_string(visit_limit_) + "u\n";
            return kernels_(defines + layout, bindings);
          },
          kBvhCounters, options.whitted_passes) {
  params_.width = static_cast<uint32_t>(std::stoul(options.params.text("bvh_width")));
  nodes_ = options.params.text("bvh_nodes") == "quantised" ? BvhNodes::Quantised : BvhNodes::Float;
  params_.top = top_of(options.params.text("bvh_top"));
  if (params_.top == BvhTop::Rebraided) params_.rebraid = options.params.real("bvh_rebraid");
  params_.max_bytes = static_cast<uint64_t>(options.params.integer("max_structure_mb")) << 20;
  const std::string config = "threads=" + std::to_string(cpu_thread_count(options));
  embree_ = rtcNewDevice(config.c_str());
  if (!embree_) throw Error("Embree: rtcNewDevice failed (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
}

BvhRenderer::~BvhRenderer() { rtcReleaseDevice(embree_); }

void BvhRenderer::prepare(const Scene& scene) {
  const auto start = std::chrono::steady_clock::now();
  const BvhScene bvh = build_bvh_scene(embree_, scene, params_);
  const uint32_t limit = std::max(bvh_mesh_build(params_.width).max_depth, bvh_top_build(params_.width).max_depth);
  Depths depths{bvh.top.depth, 0};
  for (const BvhTree& tree : bvh.meshes) depths.meshes = std::max(depths.meshes, tree.depth);
  if (std::max(depths.top, depths.meshes) > limit)
    throw Error("bvh: a BVH of the scene is " + std::to_string(std::max(depths.top, depths.meshes)) +
                " levels deep, more than the " + std::to_string(limit) + " the builder allows");

  // One node table: every mesh's BVH, then the top level's; the entry table's texel 0 is the
  // header (top root, visit bound), then one (instance, mesh node) per top-level reference.
  std::vector<glm::uvec4> nodes, entries, flat_ids;
  TriangleLayout layout;
  if (bvh.top_kind == BvhTop::Flat) {
    BvhLayout tree = encode_bvh(bvh.top, nodes_, 0);
    entries.push_back({tree.node_of_tree[0], tree.node_count(), 0, 0});
    nodes = std::move(tree.texels);
    for (uint32_t r : tree.references) {
      const FlatTriangle& t = bvh.flat_triangles[r];
      flat_ids.push_back({t.instance, t.prim, t.material, 0});
    }
    layout.triangles.push_back(std::move(tree.references));
    layout.roots.push_back(0);
  } else {
    std::vector<std::vector<uint32_t>> node_of_tree;  // per mesh: each tree node's index in the table
    uint32_t base = 0;
    for (const BvhTree& tree : bvh.meshes) {
      BvhLayout m = encode_bvh(tree, nodes_, base);
      for (uint32_t& n : m.node_of_tree) n += base;
      base += m.node_count();
      nodes.insert(nodes.end(), m.texels.begin(), m.texels.end());
      layout.triangles.push_back(std::move(m.references));
      layout.roots.push_back(m.node_of_tree[0]);
      node_of_tree.push_back(std::move(m.node_of_tree));
    }
    const BvhLayout top = encode_bvh(bvh.top, nodes_, base);
    nodes.insert(nodes.end(), top.texels.begin(), top.texels.end());
    // Each top node once, each entry's mesh nodes at most once: what a traversal can visit.
    const uint64_t bound = uint64_t(top.node_count()) + uint64_t(bvh.entries.size()) * base;
    entries.push_back({base + top.node_of_tree[0], saturated(bound), 0, 0});
    for (uint32_t r : top.references) {
      const BvhEntry& e = bvh.entries[r];
      entries.push_back({e.instance, node_of_tree[scene.instances[e.instance].mesh][e.node], 0, 0});
    }
  }
  const Scene& tables_scene = bvh.top_kind == BvhTop::Flat ? bvh.flat_world : scene;
  tables_ = std::make_unique<TriangleBuffers>(context_, tables_scene, 0, &layout);
  node_table_ = texel_table(context_, nodes, "BVH nodes");
  entry_table_ = texel_table(context_, entries, "BVH top-level entries");
  flat_ids_ = texel_table(context_, flat_ids, "flat BVH triangle ids");

  StructureStats stats;
  stats.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  // The nodes, entries and the triangles' vertices in leaf order (what the traversal reads).
  stats.bytes = (nodes.size() + entries.size() + flat_ids.size()) * sizeof(glm::uvec4) + tables_->vertices.size();
  const BvhQuality quality = bvh_quality(bvh, scene);
  stats.sah = quality.sah;
  stats.epo = quality.epo;
  stats.nodes = quality.nodes;
  stats.resolved = "top_entries=" + std::to_string(quality.entries);
  stats_ = stats;

  std::vector<KernelBinding> bindings = tables_->bindings();
  bindings.push_back({11, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, &node_table_});
  bindings.push_back({12, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, &entry_table_});
  bindings.push_back({13, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, &flat_ids_});
  depths_ = depths;
  // A visit pushes at most width - 1 items, one level of the path down each level of both trees.
  // Before set_scene: the kernels are built for it. Rounded up to 8, so that most scenes share a
  // kernel (lavapipe compiles each variant anew: the test suite's main cost).
  const uint32_t needed = std::max(1u, (depths.top + depths.meshes + 1) * (params_.width - 1));
  stack_size_ = stack_limit_ > 0 ? std::min(needed, stack_limit_) : (needed + 7u) / 8u * 8u;
  runner_.set_scene(scene, bindings);  // the scene the frames shade (flat: not the tables' world scene)
}

BackendInfo bvh_backend() {
  BackendInfo info;
  info.name = "bvh";
  info.kind = BackendKind::ComputeBvh;
  info.summary = "a SAH BVH (Embree's builder) of 2, 4 or 8 children a node traversed in a Vulkan compute kernel";
  const std::string group = "BVH (bvh)";
  info.params.push_back({"bvh_width", ParamKind::Choice, "4",
                         "children a node: 2 (the binary layout of Aila & Laine 2009), 4 or 8 (wide nodes built as Embree "
                         "builds its BVH4/BVH8)",
                         group, {"2", "4", "8"}});
  info.params.push_back({"bvh_nodes", ParamKind::Choice, "float",
                         "child boxes as floats, or quantised to 8 bits a bound on a per-node grid (the compressed wide "
                         "BVH of Ylitie, Karras & Laine 2017)",
                         group, {"float", "quantised"}});
  info.params.push_back({"bvh_top", ParamKind::Choice, "instanced",
                         "instanced: a top level over the instances' boxes; rebraided: instances opened into the top level "
                         "(partial re-braiding, Benthin et al. 2017); flat: one tree over every triangle in world space",
                         group, {"instanced", "rebraided", "flat"}});
  info.params.push_back({"bvh_rebraid", ParamKind::Real, "2",
                         "--bvh-top rebraided: top-level entries per instance, opened largest world area first",
                         group, {}, 1, 64, false, "bvh_top", "rebraided"});
  info.params.push_back(max_structure_mb_param());
  info.counters = true;
  info.create = factory<BvhRenderer>();
  return info;
}

}  // namespace sdfbench
