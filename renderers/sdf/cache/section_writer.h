#pragma once
// What a codec's encode writes: its sections, each tagged with the codec's kind and version and
// laid out in the file by encode_sdf_cache. Arrays are referenced, not copied (a cache holds
// gigabytes at most, once); single records are copied, so a codec may pass a temporary.
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <deque>
#include <type_traits>
#include <vector>

#include "renderers/sdf/cache/section_codec.h"

namespace sdfbench::sdf {

class SectionWriter {
 public:
  struct Section {
    uint32_t kind, version, index, owner, element_bytes;
    const void* data;
    uint64_t bytes, count;
  };

  void begin(const SectionCodec& codec) { codec_ = &codec; }

  // `items` must outlive the encoding.
  template <class T>
  void add(uint32_t index, uint32_t owner, const std::vector<T>& items) {
    static_assert(std::is_trivially_copyable_v<T>);
    push(index, owner, sizeof(T), items.data(), items.size());
  }
  template <class T>
  void add_one(uint32_t index, uint32_t owner, const T& item) {
    static_assert(std::is_trivially_copyable_v<T>);
    std::vector<std::byte>& copy = copies_.emplace_back(sizeof(T));
    std::memcpy(copy.data(), &item, sizeof(T));
    push(index, owner, sizeof(T), copy.data(), 1);
  }

  const std::vector<Section>& sections() const { return sections_; }

 private:
  void push(uint32_t index, uint32_t owner, size_t element_bytes, const void* data, uint64_t count) {
    assert(codec_ && index < codec_->sections.size() && codec_->sections[index].element_bytes == element_bytes);
    sections_.push_back({codec_->kind, codec_->version, index, owner, static_cast<uint32_t>(element_bytes), data,
                         count * element_bytes, count});
  }

  const SectionCodec* codec_ = nullptr;
  std::vector<Section> sections_;
  std::deque<std::vector<std::byte>> copies_;  // a deque: the records stay where they are
};

}  // namespace sdfbench::sdf
