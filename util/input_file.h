#pragma once
// The one way sdfbench opens an input file (scene, mesh, texture, cache, CSV): it must be a
// regular file (a FIFO, device or directory would hang or never end), checked on the opened
// descriptor itself, and no larger than the caller's limit, checked before anything is read.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sdfbench {

// An opened, checked input file. `what` names it in messages ("scene file", "OBJ", "SDF
// cache"); a file over `max_bytes` is refused (Error naming the file, its size and the limit)
// before anything is read. Callers with a header read it first (read_prefix), so a file that is
// not what it claims costs a few bytes, not its whole size.
class InputFile {
 public:
  InputFile(const std::filesystem::path& path, const std::string& what, uint64_t max_bytes);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  uint64_t size() const { return size_; }
  const std::string& name() const { return name_; }  // "SDF cache '/path'"
  // The first min(n, size()) bytes.
  std::vector<std::byte> read_prefix(size_t n) const;
  // The whole file (memory is committed as it is read, so an early failure costs little).
  std::vector<std::byte> read_all() const;
  // The whole file as text: a NUL byte (binary data, or a file of zeros) is refused in the chunk
  // where it appears, naming its offset, before the rest is read.
  std::string read_text() const;

 private:
  // Reads [0, size()) in chunks into `out` (a string or byte vector), calling check(chunk) on each.
  template <class Buffer, class Check>
  void read_chunks(Buffer& out, Check&& check) const;

  int fd_ = -1;
  uint64_t size_ = 0;
  std::string name_;
};

// The whole file, as text (read_text) or bytes (read_all).
std::string read_input_file(const std::filesystem::path& path, const std::string& what, uint64_t max_bytes);
std::vector<std::byte> read_input_bytes(const std::filesystem::path& path, const std::string& what, uint64_t max_bytes);

// `text` for a one-line message: control characters (a NUL, which would end the message, a
// newline) become \xNN escapes.
std::string printable(std::string_view text);

// Byte counts for messages: "1.5 GiB", "300 MiB", "12 KiB", "17 bytes".
std::string describe_bytes(uint64_t bytes);

}  // namespace sdfbench
