// Hostile input files (issue 11, classes 3, 4, 6 and 7): special files, sizes that would
// allocate gigabytes, OBJ numbers tinyobjloader reads as 0, JSON that nlohmann refuses with an
// exception. Each must be one clear error line naming the file and what is wrong, exit 1,
// quickly (every command runs under a timeout, so a hang fails instead of blocking the suite).
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <tuple>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include "harness/csv.h"
#include "harness/measurement.h"
#include "harness/thesis_tables.h"
#include "renderers/sdf/sdf_cache.h"
#include "scenes/mesh.h"
#include "scenes/scene_loader.h"
#include "tests/test_support.h"
#include "util/error.h"

namespace sdfbench {
namespace {

namespace fs = std::filesystem;

struct TimedRun {
  int exit_code = -1;
  std::string output;
  double seconds = 0.0;
};

// The binary under `timeout 20` (exit 124 when it hangs), stdout and stderr together.
TimedRun run_timed(const std::string& args) {
  TimedRun r;
  const auto start = std::chrono::steady_clock::now();
  const test::CommandResult run = test::run_command("timeout 20 " + std::string(SDFBENCH_BINARY) + " " + args);
  r.exit_code = run.exit_code;
  r.output = run.output;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// `args` as run_timed, and the peak resident memory of the command (wait4's ru_maxrss covers
// the shell, `timeout` and sdfbench below it), for inputs that used to cost gigabytes.
TimedRun run_measured(const std::string& args, long& peak_mib) {
  const fs::path out = fs::temp_directory_path() / ("sdfbench_measured_" + std::to_string(::getpid()));
  const std::string line = "timeout 20 " + std::string(SDFBENCH_BINARY) + " " + args + " > '" + out.string() + "' 2>&1";
  const auto start = std::chrono::steady_clock::now();
  TimedRun r;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", line.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  struct rusage usage {};
  EXPECT_EQ(::wait4(pid, &status, 0, &usage), pid);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(out);
  r.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  fs::remove(out);
  peak_mib = usage.ru_maxrss / 1024;
  return r;
}

// Exit 1, quickly, and exactly one line: "sdfbench: error: ..." holding every one of `words`.
void expect_one_line_error(const std::string& args, std::initializer_list<std::string> words) {
  const TimedRun r = run_timed(args);
  SCOPED_TRACE(args + "\n" + r.output);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_LT(r.seconds, 10.0);
  EXPECT_EQ(r.output.rfind("sdfbench: error: ", 0), 0u);
  EXPECT_EQ(r.output.find('\n'), r.output.size() - 1);  // one line
  for (const std::string& w : words) EXPECT_NE(r.output.find(w), std::string::npos) << "missing: " << w;
}

// The message of the Error that `f` throws ("" when it throws none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

class InputSafety : public ::testing::Test {
 protected:
  InputSafety() {
    fifo_ = dir_.path() / "fifo";
    EXPECT_EQ(::mkfifo(fifo_.c_str(), 0600), 0);
    fs::create_directory(dir_.path() / "folder");
  }
  // A FIFO (would block a reader for ever), a directory and an endless device.
  std::vector<std::pair<fs::path, std::string>> special_files() const {
    return {{fifo_, "not a regular file"}, {dir_.path() / "folder", "is a directory"}, {"/dev/zero", "not a regular file"}};
  }
  // A one-ball scene whose mesh (or texture) is `mesh_file` (`texture_file`).
  fs::path scene_with(const std::string& mesh_file, const std::string& texture_file = "") const {
    const std::string mesh = mesh_file.empty() ? R"({"builtin": "sphere"})" : R"({"file": ")" + mesh_file + R"("})";
    const std::string texture = texture_file.empty() ? "" : R"(, "texture": {"file": ")" + texture_file + R"("})";
    return dir_.write("scene.json", R"({"meshes": {"ball": )" + mesh + R"(},
      "materials": {"paint": {"albedo": [1, 1, 1])" + texture + R"(}},
      "instances": [{"mesh": "ball"}], "camera": {"position": [0, 1, 4], "look_at": [0, 0, 0]}})");
  }

  test::TempDir dir_;
  fs::path fifo_;
};

const std::string kRender = "render --backend embree --size 16x9 --frames 1 --warmup 0 ";

TEST_F(InputSafety, SpecialFilesAsSceneAreRefusedAtOnce) {
  for (const auto& [path, words] : special_files())
    expect_one_line_error(kRender + "--scene " + path.string(), {"scene file", path.string(), words});
}

TEST_F(InputSafety, SpecialFilesAsObjAreRefusedAtOnce) {
  for (const auto& [path, words] : special_files()) {
    const fs::path scene = scene_with(path.string());
    expect_one_line_error(kRender + "--scene " + scene.string(), {"meshes.ball", "OBJ", path.string(), words});
  }
}

TEST_F(InputSafety, SpecialFilesAsTextureAreRefusedAtOnce) {
  for (const auto& [path, words] : special_files()) {
    const fs::path scene = scene_with("", path.string());
    expect_one_line_error(kRender + "--scene " + scene.string(),
                          {"materials.paint.texture.file", "image", path.string(), words});
  }
}

TEST_F(InputSafety, SpecialFilesAsCacheAreRefusedEvenWithRebuild) {
  for (const auto& [path, words] : special_files()) {
    for (const char* policy : {"", " --on-bad-cache rebuild"}) {
      expect_one_line_error("render --backend sdf-cpu --scene thesis:sphere:1 --size 16x9 --frames 1 --warmup 0 --cache " +
                                path.string() + policy,
                            {"SDF cache", path.string(), words});
    }
    expect_one_line_error("inspect " + path.string(), {"SDF cache", path.string(), words});
  }
  struct stat st {};
  ASSERT_EQ(::lstat(fifo_.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the FIFO was replaced";
}

TEST_F(InputSafety, SparseHugeCacheIsRefusedByItsSize) {
  const fs::path cache = dir_.path() / "huge.sdfcache";
  { std::ofstream touch(cache); }
  fs::resize_file(cache, 20ull << 30);  // 20 GiB, sparse: reading it, or allocating its size, would fail
  expect_one_line_error("inspect " + cache.string(), {cache.string(), "20 GiB", "limit", "4.0 GiB"});
  expect_one_line_error("render --backend sdf-cpu --scene thesis:sphere:1 --size 16x9 --frames 1 --warmup 0 --cache " +
                            cache.string(),
                        {cache.string(), "20 GiB", "limit"});
}

TEST_F(InputSafety, ThesisTablesMustBeARegularFile) {
  const std::string e = error_of([&] { ThesisTables::load(fifo_); });
  EXPECT_NE(e.find("thesis tables"), std::string::npos) << e;
  EXPECT_NE(e.find("not a regular file"), std::string::npos) << e;
  EXPECT_TRUE(ThesisTables::load_default().find("6.1", "bunny", 10).has_value());  // the real one still loads
}

// CRC-32 (PNG chunks): the PNG below is patched, and libpng checks the header's CRC.
uint32_t crc32(const unsigned char* data, size_t n) {
  uint32_t c = 0xffffffffu;
  for (size_t i = 0; i < n; ++i) {
    c ^= data[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

void put_be32(std::string& s, size_t at, uint32_t v) {
  for (int k = 0; k < 4; ++k) s[at + k] = static_cast<char>(v >> (24 - 8 * k));
}

// A few-hundred-byte PNG whose header declares width x height (its pixels are missing).
void write_png_declaring(const fs::path& path, uint32_t width, uint32_t height) {
  const fs::path small = path.string() + ".1x1.png";
  auto out = OIIO::ImageOutput::create("png");
  ASSERT_TRUE(out && out->open(small.string(), OIIO::ImageSpec(1, 1, 3, OIIO::TypeDesc::UINT8)));
  const unsigned char pixel[3] = {200, 100, 50};
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixel));
  out->close();
  std::ifstream in(small, std::ios::binary);
  std::string png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(png.substr(12, 4), "IHDR");
  put_be32(png, 16, width);
  put_be32(png, 20, height);
  put_be32(png, 29, crc32(reinterpret_cast<const unsigned char*>(png.data()) + 12, 17));
  std::ofstream(path, std::ios::binary) << png;
}

TEST_F(InputSafety, TextureDeclaringHugeSizeIsRefusedBeforeDecoding) {
  const fs::path png = dir_.path() / "huge.png";
  write_png_declaring(png, 16384, 16384);
  const fs::path scene = scene_with("", png.string());
  expect_one_line_error(kRender + "--scene " + scene.string(),
                        {"materials.paint.texture.file", png.string(), "16384x16384", "16777216 texels", "256 MiB"});
  // The same header at 64x64 is read (and then fails on the missing pixels, with a clear error).
  write_png_declaring(png, 64, 64);
  const std::string e = error_of([&] { load_scene_file(scene); });
  EXPECT_NE(e.find("cannot read image"), std::string::npos) << e;
  write_png_declaring(png, 1, 1);  // and the real 1x1 image loads
  EXPECT_EQ(load_scene_file(scene).texels.size(), 1u);
}

// Textures are decoded from memory (util/image_codec.h): each format sdfbench reads loads from a
// file OpenImageIO wrote; TIFF and Radiance HDR, which it does not read, are one error naming the file.
TEST_F(InputSafety, TextureFormatsLoadFromMemory) {
  const auto write = [&](const std::string& ext, int channels, OIIO::TypeDesc type) {
    const fs::path image = dir_.path() / ("tex" + std::to_string(channels) + type.c_str() + "." + ext);
    auto out = OIIO::ImageOutput::create(ext);
    EXPECT_TRUE(out && out->open(image.string(), OIIO::ImageSpec(2, 1, channels, type)));
    const float pixels[8] = {1, 1, 1, 1, 0, 0, 0, 1};
    std::vector<float> interleaved;
    for (int p = 0; p < 2; ++p)
      for (int c = 0; c < channels; ++c) interleaved.push_back(pixels[4 * p + c]);
    EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, interleaved.data()));
    out->close();
    return image;
  };
  const std::vector<std::tuple<std::string, int, OIIO::TypeDesc>> cases = {
      {"png", 3, OIIO::TypeDesc::UINT8}, {"png", 4, OIIO::TypeDesc::UINT8}, {"png", 1, OIIO::TypeDesc::UINT8},
      {"png", 2, OIIO::TypeDesc::UINT8}, {"png", 3, OIIO::TypeDesc::UINT16}, {"jpg", 3, OIIO::TypeDesc::UINT8},
      {"exr", 3, OIIO::TypeDesc::FLOAT}, {"exr", 4, OIIO::TypeDesc::HALF},   {"exr", 1, OIIO::TypeDesc::FLOAT},
      {"tga", 3, OIIO::TypeDesc::UINT8},   {"bmp", 3, OIIO::TypeDesc::UINT8}};
  for (const auto& [ext, channels, type] : cases) {
    SCOPED_TRACE(ext + " " + std::to_string(channels) + " " + type.c_str());
    const fs::path image = write(ext, channels, type);
    const Scene scene = load_scene_file(scene_with("", image.string()));
    ASSERT_EQ(scene.texels.size(), 2u);
    EXPECT_GT(scene.texels[0].x, 0.9f);
    EXPECT_GT(scene.texels[0].z, 0.9f);
    EXPECT_LT(scene.texels[1].x, 0.1f);
  }
  for (const fs::path& unread : {write("tif", 3, OIIO::TypeDesc::UINT8), write("hdr", 3, OIIO::TypeDesc::FLOAT)}) {
    const std::string e = error_of([&] { load_scene_file(scene_with("", unread.string())); });
    EXPECT_NE(e.find("cannot read image '" + unread.string() + "'"), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
}

std::string obj_error(const std::string& text) {
  return error_of([&] { parse_obj(text, "bad.obj", "bad"); });
}

TEST(ObjInput, NonFiniteOrNonNumericCoordinatesNameFileAndLine) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (const char* coordinate : {"nan", "inf", "-inf", "abc", "1e39", "1e400", "0x10", "1.5.2", "3abc", "--1"}) {
    const std::string e = obj_error(tri + "v " + coordinate + " 0 0\nf 1 2 3\n");
    SCOPED_TRACE(coordinate);
    EXPECT_NE(e.find("OBJ 'bad.obj' line 4"), std::string::npos) << e;
    EXPECT_NE(e.find(std::string("'") + coordinate + "'"), std::string::npos) << e;
  }
  EXPECT_NE(obj_error(tri + "v 1 2\nf 1 2 3\n").find("line 4: a vertex needs 3 coordinates"), std::string::npos);
  // What OBJ writers emit is still read: signs, exponents, tabs, CRLF, w and colour columns, comments.
  const Mesh mesh = parse_obj("# c\r\nv +1 -0 .5\r\nv\t1e0 0 0 1\nv 0 1 0 0.5 0.5 0.5\n\nf 1 2 3\n", "ok.obj", "ok");
  EXPECT_EQ(mesh.positions[0], glm::vec3(1.0f, 0.0f, 0.5f));
  EXPECT_EQ(mesh.triangle_count(), 1u);
}

TEST(ObjInput, IndicesThatDoNotFitAreErrorsNotWrapped) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  struct Case {
    std::string face, words;
  };
  for (const Case& c : std::initializer_list<Case>{
           {"f 1 2 4294967299", "line 4: face uses vertex index 4294967299 but the file has 3 vertices"},
           {"f 1 2 99999999999999999999", "line 4: face vertex '99999999999999999999' is not a vertex index"},
           {"f 1 2 0", "line 4: face vertex '0' is not a vertex index"},
           {"f 1 2 x", "line 4: face vertex 'x' is not a vertex index"},
           {"f 1 2 -4", "line 4: face vertex index -4 refers before the first vertex"},
           {"f 1 2 4/1/1", "line 4: face uses vertex index 4"},
           {"f 1 2", "line 4: a face needs at least 3 vertices"},
       }) {
    const std::string e = obj_error(tri + c.face + "\n");
    EXPECT_NE(e.find(c.words), std::string::npos) << c.face << ": " << e;
  }
  // Relative, textured and forward-declared indices still load; a quad is two triangles.
  EXPECT_EQ(parse_obj(tri + "f -3/1 -2/2 -1/3\n", "ok.obj", "ok").triangle_count(), 1u);
  EXPECT_EQ(parse_obj("f 1//1 2//1 3//1 4//1\n" + tri + "v 1 1 0\n", "ok.obj", "ok").triangle_count(), 2u);
}

TEST(ObjInput, TriangleCountIsBoundedBeforeParsing) {
  // 33 027 faces of 256 corners (17 MB of text) would be 8 Mi + 250 triangles.
  std::string face = "f";
  for (int i = 0; i < 256; ++i) face += " 1";
  std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  text.reserve(text.size() + 33027 * (face.size() + 1));
  for (int i = 0; i < 33027; ++i) text += face + "\n";
  const auto start = std::chrono::steady_clock::now();
  const std::string e = obj_error(text + "\n");
  EXPECT_NE(e.find("more than 8388608 triangles (the limit for an OBJ)"), std::string::npos) << e.substr(0, 300);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

// tinyobjloader's triangulation is quadratic in a face's corners (400 000 took minutes): a face
// is refused past 256 corners by the linear pre-scan, at once; a 256-gon loads.
TEST(ObjInput, FaceCornersAreBoundedBeforeParsing) {
  std::string circle;
  for (int i = 0; i < 256; ++i)
    circle += "v " + std::to_string(std::cos(i * 0.0245437)) + " " + std::to_string(std::sin(i * 0.0245437)) + " 0\n";
  std::string face = "f";
  for (int i = 1; i <= 256; ++i) face.append(" ").append(std::to_string(i));
  EXPECT_EQ(parse_obj(circle + face + "\n", "ok.obj", "ok").triangle_count(), 254u);
  EXPECT_NE(obj_error(circle + face + " 1\n").find("OBJ 'bad.obj' line 257: a face has more than 256 vertices"), std::string::npos);
  std::string huge = circle + "f";
  for (int i = 0; i < 400000; ++i) huge.append(" ").append(std::to_string(i % 256 + 1));
  const auto start = std::chrono::steady_clock::now();
  EXPECT_NE(obj_error(huge + "\n").find("line 257: a face has more than 256 vertices"), std::string::npos);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
}

// A text input (OBJ, scene, CSV) with a NUL byte is binary: refused in the first chunk read, so
// 500 MiB of zeros (a sparse file: the test itself costs nothing) is quick and small, not the
// 2 GB it took to parse; also a NUL in the middle of an OBJ passed to parse_obj.
TEST_F(InputSafety, TextFilesOfZerosAreRefusedFromTheirFirstBytes) {
  const fs::path zeros = dir_.path() / "zeros.obj";
  { std::ofstream touch(zeros); }
  fs::resize_file(zeros, 500ull << 20);
  long peak_mib = 0;
  const TimedRun r = run_measured(kRender + "--scene " + scene_with(zeros.string()).string(), peak_mib);
  SCOPED_TRACE(r.output);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output.rfind("sdfbench: error: ", 0), 0u);
  EXPECT_EQ(r.output.find('\n'), r.output.size() - 1);
  EXPECT_NE(r.output.find("OBJ '" + zeros.string() + "' is not a text file: a NUL byte at offset 0"), std::string::npos);
  EXPECT_LT(r.seconds, 5.0);
  EXPECT_LT(peak_mib, 300);  // sdfbench's own libraries are ~100 MiB; reading the file was 2 GB
  const fs::path csv = dir_.write("late.csv", "run_index\n" + std::string(3u << 20, '1') + std::string(1, '\0') + "\n");
  const std::string e = error_of([&] { read_csv(csv); });
  EXPECT_NE(e.find("CSV '" + csv.string() + "' is not a text file: a NUL byte at offset " + std::to_string(10 + (3u << 20))),
            std::string::npos) << e;
  EXPECT_NE(obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n#" + std::string(1, '\0') + "\n").find("line 5: a NUL byte"),
            std::string::npos);
}

// An SDF cache is checked by its header before its body is read: a 4 GiB file (sparse) of zeros
// is refused for its magic, one with a real cache's header for its declared size, both at once.
TEST_F(InputSafety, HugeCacheIsRefusedByItsHeaderBeforeItsBody) {
  const fs::path scene = dir_.write("implicit.json", R"({
    "implicits": [{"shape": {"type": "ellipsoid", "radii": [1, 1, 1]}}],
    "camera": {"position": [0, 1, 4], "look_at": [0, 0, 0]}})");
  const fs::path real = dir_.path() / "real.sdfcache";
  ASSERT_EQ(run_timed("build --scene " + scene.string() + " --cache " + real.string()).exit_code, 0);
  std::string header(88, '\0');
  std::ifstream(real, std::ios::binary).read(header.data(), 88);
  const uint64_t size = (4ull << 30) - 8;  // just under the limit
  for (const bool real_header : {false, true}) {
    const fs::path cache = dir_.path() / "big.sdfcache";
    std::ofstream(cache, std::ios::binary) << (real_header ? header : std::string("NOTACACH"));
    fs::resize_file(cache, size);
    // Both readers of a cache: a render that uses it and `inspect`.
    for (const std::string& command : {"render --backend sdf-cpu --size 16x9 --frames 1 --warmup 0 --scene " + scene.string() +
                                           " --cache " + cache.string(),
                                       "inspect " + cache.string()}) {
      long peak_mib = 0;
      const TimedRun r = run_measured(command, peak_mib);
      SCOPED_TRACE(command + "\n" + r.output);
      EXPECT_EQ(r.exit_code, 1);
      EXPECT_EQ(r.output.find('\n'), r.output.size() - 1);
      EXPECT_NE(r.output.find(real_header ? "header says " + std::to_string(fs::file_size(real)) + " bytes, file has " +
                                                std::to_string(size)
                                          : "'" + cache.string() + "' is not an sdfbench SDF cache (bad magic)"),
                std::string::npos);
      EXPECT_LT(r.seconds, 5.0);
      EXPECT_LT(peak_mib, 300);  // reading it was 4 GB and 15 s
    }
  }
}

// Spreadsheets start a CSV with a UTF-8 byte-order mark; a run_index beyond 64 bits says its range.
TEST(CsvInput, ByteOrderMarkAndRunIndexRange) {
  const CsvTable t = parse_csv("\xef\xbb\xbfrun_index,x\n7,a\n18446744073709551616,b\n", "bom.csv");
  EXPECT_EQ(row_run_index(t, 0, "bom.csv"), 7u);
  const std::string e = error_of([&] { row_run_index(t, 1, "bom.csv"); });
  EXPECT_NE(e.find("run_index '18446744073709551616' is not a non-negative integer up to 18446744073709551615 (out of range)"),
            std::string::npos) << e;
}

// A NUL in a JSON name would end the message at it (what() is a C string): escaped, like a newline.
TEST(SceneInput, NulInANameIsEscapedInTheError) {
  const std::string e = error_of([&] {
    parse_scene_json(R"({"meshes": {"a\u0000b": {"builtin": "sphere"}}, "instances": [{"mesh": "c"}],
      "camera": {"position": [0, 1, 4], "look_at": [0, 0, 0]}})", "bad.json");
  });
  EXPECT_NE(e.find("unknown mesh 'c' (declared: a\\x00b)"), std::string::npos) << e;
  const std::string key = error_of([&] { parse_scene_json(R"({"came\u0000ra": 1})", "bad.json"); });
  EXPECT_NE(key.find("bad.json: came\\x00ra: unknown field"), std::string::npos) << key;
}

TEST_F(InputSafety, ObjErrorsReachTheCommandLineWithFieldFileAndLine) {
  const fs::path obj = dir_.write("nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
  expect_one_line_error(kRender + "--scene " + scene_with(obj.string()).string(),
                        {"meshes.ball", obj.string(), "line 3", "'nan' is not a finite"});
  const fs::path wrapped = dir_.write("wrapped.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4294967299\n");
  expect_one_line_error(kRender + "--scene " + scene_with(wrapped.string()).string(),
                        {"meshes.ball", wrapped.string(), "line 5", "4294967299"});
}

std::string scene_error(const std::string& json) {
  return error_of([&] { parse_scene_json(json, "bad.json"); });
}

const std::string kBall = R"({"meshes": {"ball": {"builtin": "sphere"}}, "instances": [{"mesh": "ball"}],
  )";

TEST(SceneInput, JsonNumberOverflowNamesFileLineAndColumn) {
  const std::string e = scene_error(kBall + R"("camera": {"position": [0, 1e400, 4], "look_at": [0, 0, 0]}})");
  EXPECT_EQ(e.rfind("bad.json: malformed JSON at line 2, column 30: ", 0), 0u) << e;
  EXPECT_NE(e.find("1e400"), std::string::npos) << e;
  EXPECT_EQ(e.find("json.exception"), std::string::npos) << e;
  const std::string syntax = scene_error("{\"camera\": [1,\n 2,]}");
  EXPECT_NE(syntax.find("bad.json: malformed JSON: "), std::string::npos) << syntax;
  EXPECT_NE(syntax.find("line 2"), std::string::npos) << syntax;
}

TEST_F(InputSafety, JsonNumberOverflowIsAUserErrorOnTheCommandLine) {
  const fs::path scene = dir_.write("overflow.json", kBall + R"("camera": {"position": [0, 1, 4], "look_at": [0, 0, 0]},
    "ambient": -1e400})");
  expect_one_line_error(kRender + "--scene " + scene.string(), {scene.string(), "line 3", "1e400"});
}

TEST(SceneInput, VerticalViewSaysToGiveUp) {
  const std::string e = scene_error(kBall + R"("camera": {"position": [0, 5, 0], "look_at": [0, 0, 0]}})");
  EXPECT_NE(e.find("bad.json: camera: "), std::string::npos) << e;
  EXPECT_NE(e.find("parallel to the default up [0, 1, 0]; give camera.up"), std::string::npos) << e;
  EXPECT_EQ(e.find("missing required field"), std::string::npos) << e;
  EXPECT_NO_THROW(parse_scene_json(kBall + R"("camera": {"position": [0, 5, 0], "look_at": [0, 0, 0], "up": [0, 0, -1]}})",
                                   "ok.json"));
}

TEST(SceneInput, HugeIntegersAreReportedAsWritten) {
  const std::string e = scene_error(kBall + R"("camera": {"position": [0, 1, 4], "look_at": [0, 0, 0]},
    "render": {"width": 18446744073709551615}})");
  EXPECT_NE(e.find("render.width"), std::string::npos) << e;
  EXPECT_NE(e.find("18446744073709551615"), std::string::npos) << e;
  EXPECT_NE(e.find("16384"), std::string::npos) << e;
  const std::string negative = scene_error(kBall + R"("camera": {"position": [0, 1, 4], "look_at": [0, 0, 0]},
    "render": {"height": -9223372036854775807}})");
  EXPECT_NE(negative.find("-9223372036854775807"), std::string::npos) << negative;
}

TEST_F(InputSafety, ImplicitOnlySceneCacheIsReadBack) {
  const fs::path scene = dir_.write("implicit.json", R"({
    "implicits": [{"shape": {"type": "ellipsoid", "radii": [1, 1, 1]}}],
    "camera": {"position": [0, 1, 4], "look_at": [0, 0, 0]}})");
  const fs::path cache = dir_.path() / "implicit.sdfcache";
  const TimedRun build = run_timed("build --scene " + scene.string() + " --cache " + cache.string());
  ASSERT_EQ(build.exit_code, 0) << build.output;
  const TimedRun render = run_timed("render --backend sdf-cpu --size 16x9 --frames 1 --warmup 0 --scene " + scene.string() +
                               " --cache " + cache.string());
  EXPECT_EQ(render.exit_code, 0) << render.output;
  EXPECT_NE(render.output.find("build skipped"), std::string::npos) << render.output;
  const TimedRun inspect = run_timed("inspect " + cache.string());
  EXPECT_EQ(inspect.exit_code, 0) << inspect.output;
  EXPECT_NE(inspect.output.find("(0 meshes, 0 instances)"), std::string::npos) << inspect.output;
}

}  // namespace
}  // namespace sdfbench
