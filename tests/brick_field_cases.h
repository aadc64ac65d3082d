#pragma once
// A brick field to build in a test (mesh, voxels along its longest side, stored format) and its
// gtest parameter name, shared by the brick field tests on the CPU and on the device.
#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "renderers/sdf_bricks/brick_field.h"

namespace sdfbench::test {

struct FieldCase {
  const char* mesh;
  uint32_t voxels;
  sdf::SdfFormat format;
};

inline std::string field_case_name(const testing::TestParamInfo<FieldCase>& info) {
  return std::string(info.param.mesh) + "_" + std::to_string(info.param.voxels) + "_" + sdf::to_string(info.param.format);
}

}  // namespace sdfbench::test
