#include <cmath>

#include <gtest/gtest.h>

#include "harness/image_agreement.h"
#include "renderers/shading/gpu_types.h"

namespace sdfbench {
namespace {

FrameImages flat_frame(uint32_t w, uint32_t h, uint32_t id) {
  FrameImages f;
  f.width = w;
  f.height = h;
  const size_t n = static_cast<size_t>(w) * h;
  f.color.assign(n, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
  f.depth.assign(n, 10.0f);
  f.instance_id.assign(n, id);
  f.primitive_id.assign(n, 0);
  f.normal.assign(n, glm::vec3(0, 1, 0));
  return f;
}

TEST(ImageAgreement, IdenticalFramesAgreeFully) {
  const FrameImages a = flat_frame(8, 4, 3);
  const Agreement g = compare_frames(a, a);
  EXPECT_DOUBLE_EQ(g.hit_percent, 100.0);
  EXPECT_DOUBLE_EQ(g.id_percent, 100.0);
  EXPECT_DOUBLE_EQ(g.depth_p99, 0.0);
  EXPECT_TRUE(std::isinf(g.psnr));
  EXPECT_EQ(check_thresholds(g, AgreementThresholds{}), "");
}

TEST(ImageAgreement, CountsMaskIdDepthAndColourDifferences) {
  const FrameImages ref = flat_frame(10, 10, 3);
  FrameImages test = ref;
  for (int i = 0; i < 10; ++i) test.instance_id[i] = shading::NO_INSTANCE_VALUE;  // 10 % missed
  for (int i = 10; i < 15; ++i) test.instance_id[i] = 4;                           // 5 % wrong id
  for (int i = 20; i < 100; ++i) test.depth[i] = 10.5f;                            // 5 % relative depth error
  test.color[50] = glm::vec4(1.0f);                                                // one pixel off by 0.5
  const Agreement g = compare_frames(test, ref);
  EXPECT_DOUBLE_EQ(g.hit_percent, 90.0);
  EXPECT_DOUBLE_EQ(g.id_percent, 85.0);
  EXPECT_NEAR(g.depth_p99, 0.05, 1e-6);
  EXPECT_NEAR(g.over_threshold_percent, 1.0, 1e-9);
  EXPECT_NEAR(g.psnr, 20.0 * std::log10(1.0 / std::sqrt(0.25 / 100.0)), 0.01);  // one pixel, 3 channels off by .5
  const std::string failed = check_thresholds(g, AgreementThresholds{});
  EXPECT_NE(failed.find("hit-mask"), std::string::npos);
  EXPECT_NE(failed.find("instance-id"), std::string::npos);
  EXPECT_NE(failed.find("depth"), std::string::npos);
}

// A tiny object: one wrong pixel out of 50 is 98 % id agreement, passing only through the
// pixel allowance; three wrong pixels fail.
TEST(ImageAgreement, IdThresholdAllowsAFewPixelsOnTinyObjects) {
  FrameImages ref = flat_frame(10, 10, shading::NO_INSTANCE_VALUE);
  for (int i = 0; i < 50; ++i) ref.instance_id[i] = 3;
  FrameImages test = ref;
  test.instance_id[0] = 7;
  Agreement g = compare_frames(test, ref);
  EXPECT_DOUBLE_EQ(g.id_percent, 98.0);
  EXPECT_EQ(g.id_mismatches, 1u);
  EXPECT_EQ(check_thresholds(g, AgreementThresholds{}), "");
  test.instance_id[1] = test.instance_id[2] = 7;
  g = compare_frames(test, ref);
  EXPECT_EQ(g.id_mismatches, 3u);
  EXPECT_NE(check_thresholds(g, AgreementThresholds{}).find("instance-id"), std::string::npos);
}

TEST(ImageAgreement, FloorAndSkyAreNotInstanceHits) {
  const FrameImages ref = flat_frame(4, 4, shading::FLOOR_INSTANCE_VALUE);
  const FrameImages test = flat_frame(4, 4, shading::NO_INSTANCE_VALUE);
  const Agreement g = compare_frames(test, ref);
  EXPECT_DOUBLE_EQ(g.hit_percent, 100.0);  // neither hit an instance
  EXPECT_DOUBLE_EQ(g.id_percent, 100.0);   // no pixel where either hit an instance
}

}  // namespace
}  // namespace sdfbench
