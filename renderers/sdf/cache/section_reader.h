#pragma once
// What a codec's decode reads: its own sections, already checked by decode_sdf_cache against the
// file (inside the payload, aligned, no overlap, the codec's element size, owner in range, each
// present once). What they hold is the codec's to check; every failure is an Error naming the
// file and the problem.
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "renderers/sdf/cache/section_codec.h"
#include "util/error.h"

namespace sdfbench::sdf {

[[noreturn]] inline void fail_invalid_cache(const std::string& source, const std::string& what) {
  throw Error("SDF cache '" + source + "' is invalid: " + what + " (rebuild it with `sdfbench build --cache`)");
}

// "mesh 0 cell_begin", "octree nodes": how inspect and messages name a section.
inline std::string section_name(const SectionCodec& codec, uint32_t index, uint32_t owner) {
  const SectionSpec& spec = codec.sections.at(index);
  return spec.per_mesh ? "mesh " + std::to_string(owner) + " " + spec.name : std::string(spec.name);
}

struct LocatedSection {
  uint64_t offset = 0, count = 0;
};

class SectionReader {
 public:
  // `located[index][owner]`: each of the codec's sections (per mesh: one per mesh).
  SectionReader(std::span<const std::byte> file, std::string source, const SectionCodec& codec, uint32_t mesh_count,
                std::vector<std::vector<LocatedSection>> located)
      : file_(file), source_(std::move(source)), codec_(codec), mesh_count_(mesh_count), located_(std::move(located)) {}

  [[noreturn]] void fail(const std::string& what) const { fail_invalid_cache(source_, what); }
  void require(bool ok, const std::string& what) const {
    if (!ok) fail(what);
  }
  uint32_t mesh_count() const { return mesh_count_; }

  template <class T>
  std::vector<T> section(uint32_t index, uint32_t owner = 0) const {
    const LocatedSection& s = locate<T>(index, owner);
    std::vector<T> items(s.count);
    if (s.count) std::memcpy(items.data(), file_.data() + s.offset, s.count * sizeof(T));
    return items;
  }
  template <class T>
  T single(uint32_t index, uint32_t owner = 0) const {
    const LocatedSection& s = locate<T>(index, owner);
    require(s.count == 1, section_name(codec_, index, owner) + " holds " + std::to_string(s.count) + " records, expected 1");
    T item;
    std::memcpy(&item, file_.data() + s.offset, sizeof item);
    return item;
  }

 private:
  template <class T>
  const LocatedSection& locate(uint32_t index, uint32_t owner) const {
    assert(codec_.sections.at(index).element_bytes == sizeof(T));
    return located_.at(index).at(owner);
  }

  std::span<const std::byte> file_;
  std::string source_;
  const SectionCodec& codec_;
  uint32_t mesh_count_;
  std::vector<std::vector<LocatedSection>> located_;
};

}  // namespace sdfbench::sdf
