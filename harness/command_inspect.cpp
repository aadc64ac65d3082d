// `sdfbench inspect FILE`: validate an SDF cache completely and describe it.
#include <cstdio>
#include <string>
#include <vector>

#include "harness/commands.h"
#include "renderers/sdf/cache/section_codec.h"
#include "renderers/sdf/sdf_cache_format.h"
#include "util/input_file.h"

namespace sdfbench {
namespace {

void run_inspect(const std::string& path) {
  // The header first: a file of gigabytes that is no cache is refused for its first bytes.
  const InputFile file(path, "SDF cache", sdf::kMaxSdfCacheBytes);
  const std::vector<std::byte> head = file.read_prefix(sdf::kSdfCacheHeaderBytes);
  sdf::check_sdf_cache_header(head, file.size(), path);
  const sdf::SdfCacheContents c = sdf::decode_sdf_cache(file.read_all(), path);
  std::printf("file         %s (%llu bytes), valid\n", path.c_str(), static_cast<unsigned long long>(c.file_bytes));
  std::printf("version      %u\n", c.version);
  std::printf("scene hash   %016llx (%zu meshes, %u instances)\n", static_cast<unsigned long long>(c.scene_hash),
              c.sdf.mesh_grids.size(), c.instance_count);
  std::string names;
  for (const sdf::StoredStructure& s : c.structures)
    names += (names.empty() ? "" : ", ") + s.name + " v" + std::to_string(s.version) + (s.read ? "" : " (not read)");
  std::printf("structures   %s\n", names.c_str());
  // Each structure describes itself (its codec); one this sdfbench cannot read is only named.
  for (const sdf::StoredStructure& s : c.structures) {
    const sdf::SectionCodec* codec = sdf::codec_of_kind(s.kind);
    if (!s.read) {
      std::printf("%-12s version %u: not read (%s)\n", s.name.c_str(), s.version,
                  codec ? ("this sdfbench reads version " + std::to_string(codec->version)).c_str() : "unknown to this sdfbench");
      continue;
    }
    for (const std::string& line : codec->summary(c)) std::printf("%s\n", line.c_str());
  }
  std::printf("sections     %-28s %12s %12s %14s\n", "name", "offset", "elements", "bytes");
  for (const sdf::SdfCacheSection& s : c.sections)
    std::printf("             %-28s %12llu %12llu %14llu\n", s.name.c_str(), static_cast<unsigned long long>(s.offset),
                static_cast<unsigned long long>(s.count), static_cast<unsigned long long>(s.bytes));
}

}  // namespace

void register_inspect_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("inspect", "Validate an SDF cache file completely and print its version, structures (each "
                                                "with its parameters), scene hash and sections (exit 1 when invalid)");
  cmd->add_option("file", *path, "cache written by `sdfbench build --cache`")->required();
  cmd->callback([path] { run_inspect(*path); });
}

}  // namespace sdfbench
