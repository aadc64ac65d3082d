#include "harness/image_output.h"

#include <algorithm>
#include <cctype>
#include <memory>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "renderers/shading/gpu_types.h"
#include "scenes/error.h"
#include "util/atomic_file.h"

namespace sdfbench {
namespace {

namespace fs = std::filesystem;

// An image writer for `path`'s format that can encode into memory, or Error naming `what`.
std::unique_ptr<OIIO::ImageOutput> create_output(const fs::path& path, const std::string& what) {
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out) throw Error(what + " '" + path.string() + "': unsupported image format (use .png, .exr, .tif, ...)");
  if (!out->supports("ioproxy"))
    throw Error(what + " '" + path.string() + "': OpenImageIO cannot write " + out->format_name() +
                " images to memory, which sdfbench needs to write them safely (use .png, .exr, .tif, ...)");
  return out;
}

// Encoded in memory, then written with write_file_atomically: the image goes through the one
// safe way to write an output, never through a file OpenImageIO opens by name.
void write_atomically(const fs::path& path, const OIIO::ImageSpec& spec, const void* pixels, OIIO::TypeDesc type) {
  auto out = create_output(path, "cannot write");
  std::vector<unsigned char> encoded;
  OIIO::Filesystem::IOVecOutput memory(encoded);
  if (!out->set_ioproxy(&memory) || !out->open(path.string(), spec) || !out->write_image(type, pixels) || !out->close())
    throw Error("cannot write '" + path.string() + "': " + out->geterror());
  out.reset();
  write_file_atomically(path, std::as_bytes(std::span(encoded.data(), encoded.size())));
}

bool is_exr(const fs::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".exr";
}

float id_to_float(uint32_t id) {
  if (id == shading::NO_INSTANCE_VALUE) return -1.0f;
  if (id == shading::FLOOR_INSTANCE_VALUE) return -2.0f;
  return static_cast<float>(id);
}

// A viridis-like colour map (perceptually ordered, readable in grey and by colour-blind
// readers), piecewise linear through five of viridis' colours; x in [0, 1].
glm::vec3 colour_map(float x) {
  static const glm::vec3 stops[] = {{0.267f, 0.005f, 0.329f}, {0.231f, 0.322f, 0.545f}, {0.129f, 0.569f, 0.549f},
                                    {0.369f, 0.788f, 0.384f}, {0.993f, 0.906f, 0.144f}};
  const float s = glm::clamp(x, 0.0f, 1.0f) * 4.0f;
  const int i = std::min(static_cast<int>(s), 3);
  return glm::mix(stops[i], stops[i + 1], s - static_cast<float>(i));
}

}  // namespace

void check_image_path(const fs::path& path, const char* what) {
  check_output_path(path, what);
  create_output(path, what);
}

void check_aov_path(const fs::path& path, const char* what) {
  if (!path.empty() && !is_exr(path))
    throw Error(std::string(what) + " '" + path.string() + "': the AOVs are 7 float channels, which only OpenEXR holds (use .exr)");
  check_image_path(path, what);
}

void write_color_image(const FrameImages& images, const fs::path& path) {
  OIIO::ImageSpec spec(static_cast<int>(images.width), static_cast<int>(images.height), 4, OIIO::TypeDesc::FLOAT);
  const std::string ext = path.extension().string();
  if (ext != ".exr" && ext != ".hdr") spec.set_format(OIIO::TypeDesc::UINT8);
  write_atomically(path, spec, images.color.data(), OIIO::TypeDesc::FLOAT);
}

HeatmapRange write_heatmap(const std::vector<uint32_t>& values, uint32_t width, uint32_t height, const fs::path& path) {
  HeatmapRange range;
  if (!values.empty()) {
    std::vector<uint32_t> sorted = values;
    std::sort(sorted.begin(), sorted.end());
    range = {sorted[(sorted.size() - 1) * 99 / 100], sorted.back()};
  }
  std::vector<glm::vec3> rgb;
  rgb.reserve(values.size());
  for (uint32_t v : values)
    rgb.push_back(colour_map(range.top > 0 ? static_cast<float>(v) / static_cast<float>(range.top) : 0.0f));
  OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), 3, OIIO::TypeDesc::UINT8);
  write_atomically(path, spec, rgb.data(), OIIO::TypeDesc::FLOAT);
  return range;
}

void write_aov_image(const FrameImages& images, const fs::path& path) {
  check_aov_path(path, "--aov");
  constexpr int kChannels = 7;
  OIIO::ImageSpec spec(static_cast<int>(images.width), static_cast<int>(images.height), kChannels, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"hit", "depth", "instance_id", "primitive_id", "N.x", "N.y", "N.z"};
  const size_t pixels = images.depth.size();
  std::vector<float> data(pixels * kChannels);
  for (size_t i = 0; i < pixels; ++i) {
    float* px = &data[i * kChannels];
    const uint32_t id = images.instance_id[i];
    px[0] = id < shading::FLOOR_INSTANCE_VALUE ? 1.0f : 0.0f;  // an instance, not floor or sky
    px[1] = images.depth[i];
    px[2] = id_to_float(id);
    px[3] = id == shading::NO_INSTANCE_VALUE ? -1.0f : static_cast<float>(images.primitive_id[i]);
    px[4] = images.normal[i].x;
    px[5] = images.normal[i].y;
    px[6] = images.normal[i].z;
  }
  write_atomically(path, spec, data.data(), OIIO::TypeDesc::FLOAT);
}

}  // namespace sdfbench
