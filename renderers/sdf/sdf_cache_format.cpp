#include "renderers/sdf/sdf_cache_format.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <optional>

#include "renderers/sdf/cache/section_codec.h"
#include "renderers/sdf/cache/section_reader.h"
#include "renderers/sdf/cache/section_writer.h"
#include "util/error.h"
#include "util/fnv1a.h"

namespace sdfbench::sdf {
namespace {

static_assert(std::endian::native == std::endian::little, "the cache format is little-endian");

constexpr char kMagic[8] = {'S', 'D', 'F', 'B', 'C', 'A', 'C', 'H'};
constexpr uint32_t kMaxMeshes = 1u << 16;
constexpr uint32_t kMaxInstances = 1u << 24;

struct FileHeader {
  char magic[8];
  uint32_t version, header_bytes;
  uint64_t file_bytes, scene_hash;
  uint32_t mesh_count, instance_count, section_count, reserved;
};
struct SectionEntry {
  uint32_t kind, version, index, owner, element_bytes, reserved;
  uint64_t offset, count;
};
static_assert(sizeof(FileHeader) == kSdfCacheHeaderBytes && sizeof(SectionEntry) == 40);

uint64_t align8(uint64_t n) { return (n + 7) & ~uint64_t{7}; }

// The fixed header against the file's size: what can be checked before the body is read.
FileHeader check_header(std::span<const std::byte> head, uint64_t file_bytes, const std::string& source) {
  if (file_bytes < sizeof(FileHeader) + sizeof(uint64_t) || head.size() < sizeof(FileHeader))
    fail_invalid_cache(source, "file is " + std::to_string(file_bytes) + " bytes, too short for a cache header");
  FileHeader h;
  std::memcpy(&h, head.data(), sizeof h);
  if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0)
    throw Error("'" + source + "' is not an sdfbench SDF cache (bad magic)");
  if (h.version != kSdfCacheVersion)
    throw Error("SDF cache '" + source + "' has format version " + std::to_string(h.version) + "; this sdfbench reads version " +
                std::to_string(kSdfCacheVersion) + " (" + (h.version < kSdfCacheVersion ? "written by an older sdfbench; " : "") +
                "rebuild it with `sdfbench build --cache`, or delete it)");
  if (h.header_bytes != sizeof(FileHeader)) fail_invalid_cache(source, "header size " + std::to_string(h.header_bytes));
  if (h.file_bytes != file_bytes)
    fail_invalid_cache(source, "truncated or extended: header says " + std::to_string(h.file_bytes) + " bytes, file has " +
                                   std::to_string(file_bytes));
  return h;
}

// The section table, checked for what every section shares: inside the payload, aligned, not
// overlapping; for a codec this sdfbench reads, its element size, owner and each section once.
// A structure of an unknown kind or another codec version is bounds-checked and then skipped.
class SectionTable {
 public:
  SectionTable(std::span<const std::byte> bytes, const std::string& source, const FileHeader& h)
      : bytes_(bytes), source_(source), mesh_count_(h.mesh_count) {
    const uint64_t table_end = sizeof(FileHeader) + uint64_t{h.section_count} * sizeof(SectionEntry);
    const uint64_t payload_end = bytes.size() - sizeof(uint64_t);
    require(table_end <= payload_end, "section table runs past the end of the file");
    entries_.resize(h.section_count);
    if (!entries_.empty()) std::memcpy(entries_.data(), bytes.data() + sizeof(FileHeader), entries_.size() * sizeof(SectionEntry));
    for (uint32_t i = 0; i < entries_.size(); ++i) check_entry(entries_[i], i, table_end, payload_end);
    check_overlaps();
  }

  const std::vector<StoredStructure>& structures() const { return structures_; }

  // The codec's sections, each present once; null when the file does not hold its structure
  // (or holds it in another codec version).
  std::optional<SectionReader> reader(const SectionCodec& codec) const {
    const auto found = std::find_if(structures_.begin(), structures_.end(), [&](auto& s) { return s.kind == codec.kind; });
    if (found == structures_.end() || !found->read) return std::nullopt;
    std::vector<std::vector<LocatedSection>> located(codec.sections.size());
    std::vector<std::vector<bool>> seen(codec.sections.size());
    for (size_t k = 0; k < codec.sections.size(); ++k) {
      const size_t owners = codec.sections[k].per_mesh ? mesh_count_ : 1;
      located[k].resize(owners);
      seen[k].resize(owners);
    }
    for (const SectionEntry& e : entries_) {
      if (e.kind != codec.kind) continue;
      require(!seen[e.index][e.owner], codec.name + std::string(": ") + section_name(codec, e.index, e.owner) + " appears twice");
      seen[e.index][e.owner] = true;
      located[e.index][e.owner] = {e.offset, e.count};
    }
    for (uint32_t k = 0; k < seen.size(); ++k)
      for (uint32_t owner = 0; owner < seen[k].size(); ++owner)
        require(seen[k][owner], std::string(codec.name) + ": " + section_name(codec, k, owner) + " is missing");
    return SectionReader(bytes_, source_, codec, mesh_count_, std::move(located));
  }

  std::vector<SdfCacheSection> describe() const {
    std::vector<SdfCacheSection> out;
    for (const SectionEntry& e : entries_) {
      const SectionCodec* codec = readable(e) ? codec_of_kind(e.kind) : nullptr;
      const std::string name = codec ? section_name(*codec, e.index, e.owner)
                                     : "kind " + std::to_string(e.kind) + " v" + std::to_string(e.version) + " section " +
                                           std::to_string(e.index) + " owner " + std::to_string(e.owner);
      out.push_back({name, e.offset, e.count, e.count * e.element_bytes});
    }
    return out;
  }

 private:
  void require(bool ok, const std::string& what) const {
    if (!ok) fail_invalid_cache(source_, what);
  }
  bool readable(const SectionEntry& e) const {
    const SectionCodec* codec = codec_of_kind(e.kind);
    return codec && codec->version == e.version;
  }

  void check_entry(const SectionEntry& e, uint32_t i, uint64_t table_end, uint64_t payload_end) {
    const std::string where = "section " + std::to_string(i);
    note_structure(e, where);
    std::string name = where;
    if (const SectionCodec* codec = codec_of_kind(e.kind); codec && codec->version == e.version) {
      require(e.index < codec->sections.size(), where + " (" + codec->name + ") has unknown index " + std::to_string(e.index));
      const SectionSpec& spec = codec->sections[e.index];
      require(spec.per_mesh ? e.owner < mesh_count_ : e.owner == 0,
              where + " (" + codec->name + " " + spec.name + ") has owner " + std::to_string(e.owner));
      name = section_name(*codec, e.index, e.owner);
      require(e.element_bytes == spec.element_bytes, name + ": element size " + std::to_string(e.element_bytes));
    } else {
      require(e.element_bytes >= 1, where + ": element size 0");
    }
    require(e.offset % 8 == 0 && e.offset >= table_end && e.offset <= payload_end,
            name + ": offset " + std::to_string(e.offset) + " outside the payload");
    require(e.count <= (payload_end - e.offset) / e.element_bytes,
            name + ": " + std::to_string(e.count) + " elements run past the end of the file");
  }

  // One version per structure in a file.
  void note_structure(const SectionEntry& e, const std::string& where) {
    for (const StoredStructure& s : structures_)
      if (s.kind == e.kind) {
        require(s.version == e.version, where + " has " + s.name + " in version " + std::to_string(e.version) + " and " +
                                            std::to_string(s.version));
        return;
      }
    const SectionCodec* codec = codec_of_kind(e.kind);
    structures_.push_back({e.kind, e.version, codec ? codec->name : "kind " + std::to_string(e.kind),
                           codec && codec->version == e.version});
  }

  void check_overlaps() const {
    std::vector<const SectionEntry*> by_offset;  // empty sections hold no bytes to overlap (a grid without far cells)
    for (const SectionEntry& e : entries_)
      if (e.count != 0) by_offset.push_back(&e);
    std::sort(by_offset.begin(), by_offset.end(), [](auto a, auto b) { return a->offset < b->offset; });
    const std::vector<SdfCacheSection> names = describe();
    auto name_of = [&](const SectionEntry* e) { return names[static_cast<size_t>(e - entries_.data())].name; };
    for (size_t i = 1; i < by_offset.size(); ++i) {
      const SectionEntry& a = *by_offset[i - 1];
      require(a.offset + a.count * a.element_bytes <= by_offset[i]->offset, name_of(&a) + " overlaps " + name_of(by_offset[i]));
    }
  }

  std::span<const std::byte> bytes_;
  std::string source_;
  uint32_t mesh_count_;
  std::vector<SectionEntry> entries_;
  std::vector<StoredStructure> structures_;
};

std::vector<std::byte> lay_out(FileHeader header, const std::vector<SectionWriter::Section>& sections) {
  header.section_count = static_cast<uint32_t>(sections.size());
  uint64_t offset = align8(sizeof(FileHeader) + sections.size() * sizeof(SectionEntry));
  std::vector<SectionEntry> table;
  for (const SectionWriter::Section& s : sections) {
    table.push_back({s.kind, s.version, s.index, s.owner, s.element_bytes, 0, offset, s.count});
    offset = align8(offset + s.bytes);
  }
  header.file_bytes = offset + sizeof(uint64_t);
  std::vector<std::byte> out(header.file_bytes, std::byte{0});
  std::memcpy(out.data(), &header, sizeof header);
  std::memcpy(out.data() + sizeof header, table.data(), table.size() * sizeof(SectionEntry));
  for (size_t i = 0; i < sections.size(); ++i)
    if (sections[i].bytes) std::memcpy(out.data() + table[i].offset, sections[i].data, sections[i].bytes);
  reseal_sdf_cache(out);
  return out;
}

}  // namespace

void reseal_sdf_cache(std::span<std::byte> bytes) {
  if (bytes.size() < sizeof(uint64_t)) return;
  const uint64_t sum = fnv1a64(bytes.first(bytes.size() - sizeof sum));
  std::memcpy(bytes.data() + bytes.size() - sizeof sum, &sum, sizeof sum);
}

std::vector<std::byte> encode_sdf_cache(const SdfCacheContents& c) {
  FileHeader h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.version = kSdfCacheVersion;
  h.header_bytes = sizeof(FileHeader);
  h.scene_hash = c.scene_hash;
  h.mesh_count = static_cast<uint32_t>(c.sdf.mesh_grids.size());
  h.instance_count = c.instance_count;
  SectionWriter out;
  for (const SectionCodec* codec : section_codecs()) {
    if (codec->optional && !codec->holds(c.sdf)) continue;
    out.begin(*codec);
    codec->encode(c, out);
  }
  return lay_out(h, out.sections());
}

void check_sdf_cache_header(std::span<const std::byte> head, uint64_t file_bytes, const std::string& source) {
  check_header(head, file_bytes, source);
}

SdfCacheContents decode_sdf_cache(std::span<const std::byte> bytes, const std::string& source) {
  const FileHeader h = check_header(bytes, bytes.size(), source);
  uint64_t stored;
  std::memcpy(&stored, bytes.data() + bytes.size() - sizeof stored, sizeof stored);
  if (stored != fnv1a64(bytes.first(bytes.size() - sizeof stored))) fail_invalid_cache(source, "checksum mismatch (corrupted file)");
  // No meshes or instances is a scene of implicit objects only (its hash is one empty cell).
  if (h.mesh_count > kMaxMeshes) fail_invalid_cache(source, "mesh count " + std::to_string(h.mesh_count));
  if (h.instance_count > kMaxInstances) fail_invalid_cache(source, "instance count " + std::to_string(h.instance_count));
  const SectionTable table(bytes, source, h);
  SdfCacheContents c;
  c.version = h.version;
  c.scene_hash = h.scene_hash;
  c.instance_count = h.instance_count;
  c.file_bytes = h.file_bytes;
  for (const SectionCodec* codec : section_codecs()) {
    const std::optional<SectionReader> in = table.reader(*codec);
    if (in) {
      codec->decode(*in, c);
      continue;
    }
    if (codec->optional) continue;  // not held: completed or stale for whoever asks for it
    const auto other = std::find_if(table.structures().begin(), table.structures().end(),
                                    [&](const StoredStructure& s) { return s.kind == codec->kind; });
    if (other != table.structures().end())  // stale as a whole: every backend needs it
      throw Error("SDF cache '" + source + "' holds " + codec->name + " in codec version " + std::to_string(other->version) +
                  "; this sdfbench reads version " + std::to_string(codec->version) +
                  " (rebuild it with `sdfbench build --cache`, or delete it)");
    fail_invalid_cache(source, std::string("it holds no ") + codec->name);
  }
  c.structures = table.structures();
  c.sections = table.describe();
  return c;
}

}  // namespace sdfbench::sdf
