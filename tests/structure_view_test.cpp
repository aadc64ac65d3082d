// Structure views (thesis figures 6.6-6.7): the overlay paints hash cells and octree leaves at
// the frame's hit points, and the command line checks its arguments.
#include <gtest/gtest.h>

#include "harness/structure_view.h"
#include "renderers/backend_registry.h"
#include "renderers/renderer.h"
#include "scenes/scene_source.h"
#include "tests/test_support.h"
#include "util/error.h"

namespace sdfbench {
namespace {

TEST(StructureView, PaintsHitPointsInsideTheHashOnly) {
  const Scene scene = load_scene("thesis:sphere:20");
  sdf::MeshGridParams mesh_grid;
  mesh_grid.cells_per_extent = 8;
  sdf::SceneHashParams scene_hash;
  scene_hash.octree_depth = 2;
  const sdf::SceneSdf sdf = sdf::build_scene_sdf(scene, mesh_grid, scene_hash);
  auto renderer = create_renderer("embree", BackendOptions{});
  renderer->prepare(scene);
  const FrameRequest request{96, 54, RenderMode::Primary, true};
  const FrameImages frame = renderer->render(request).images;
  const FrameImages hash = overlay_structure(frame, scene, request, sdf.hash, StructureView::Hash,
                                             default_view_cell(frame, scene, request, sdf.hash));
  size_t changed = 0, sky_changed = 0;
  for (size_t i = 0; i < frame.color.size(); ++i) {
    const bool differs = frame.color[i] != hash.color[i];
    changed += differs;
    sky_changed += differs && frame.depth[i] <= 0.0f;
  }
  EXPECT_GT(changed, frame.color.size() / 20) << "the hash covers the instances: some pixels must be tinted";
  EXPECT_EQ(sky_changed, 0u) << "the sky has no hit point and must stay untouched";
  const glm::uvec3 cell = default_view_cell(frame, scene, request, sdf.hash);
  const FrameImages octree = overlay_structure(frame, scene, request, sdf.hash, StructureView::Octree, cell);
  EXPECT_NE(octree.color, frame.color);
  EXPECT_THROW(overlay_structure(frame, scene, request, sdf.hash, StructureView::Octree, sdf.hash.dims), Error);
}

TEST(StructureView, CommandLine) {
  test::TempDir dir;
  const std::string base = "render --scene thesis:sphere:4 --backend sdf-cpu --size 48x27 --frames 1 --warmup 0 "
                           "--cells-per-extent 8 ";
  test::CommandResult r = test::run_sdfbench(base + "--view octree --out " + (dir.path() / "v.png").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("octree of cell"), std::string::npos) << r.output;
  r = test::run_sdfbench(base + "--view hash");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("give --out"), std::string::npos) << r.output;
  r = test::run_sdfbench(base + "--view octree --view-cell 999,0,0 --out " + (dir.path() / "w.png").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("outside the hash"), std::string::npos) << r.output;
  r = test::run_sdfbench(base + "--view bvh --out " + (dir.path() / "x.png").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
}

}  // namespace
}  // namespace sdfbench
