#include "util/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string_view>

#include "util/error.h"


namespace sdfbench {

namespace {

// Big enough for few system calls, small enough that a hostile file's first chunk costs nothing.
constexpr size_t kChunkBytes = 1u << 20;

}  // namespace

InputFile::InputFile(const std::filesystem::path& path, const std::string& what, uint64_t max_bytes)
    : name_(what + " '" + printable(path.string()) + "'") {
  // The system call would read the name up to the NUL: another file.
  if (path.string().find('\0') != std::string::npos) throw Error(name_ + ": a file name cannot hold a NUL byte");
  // O_NONBLOCK: opening a FIFO must not wait for a writer; the type check below refuses it.
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd_ < 0) {
    if (errno == ENOENT) throw Error(name_ + " does not exist");
    throw Error("cannot open " + name_ + ": " + std::strerror(errno));
  }
  try {
    struct stat st {};
    if (::fstat(fd_, &st) != 0) throw Error("cannot read " + name_ + ": " + std::strerror(errno));
    if (S_ISDIR(st.st_mode)) throw Error(name_ + " is a directory, not a file");
    if (!S_ISREG(st.st_mode)) throw Error(name_ + " is not a regular file (a FIFO, socket or device)");
    size_ = static_cast<uint64_t>(st.st_size);
    if (size_ > max_bytes)
      throw Error(name_ + " is " + describe_bytes(size_) + ", more than the limit for a " + what + " (" +
                  describe_bytes(max_bytes) + ")");
  } catch (...) {
    ::close(fd_);
    throw;
  }
}

InputFile::~InputFile() { ::close(fd_); }

template <class Buffer, class Check>
void InputFile::read_chunks(Buffer& out, Check&& check) const {
  // reserve, not resize: pages are committed only as they are filled.
  out.reserve(size_);
  uint64_t done = 0;
  while (done < size_) {
    const size_t want = static_cast<size_t>(std::min<uint64_t>(kChunkBytes, size_ - done));
    out.resize(done + want);
    auto* at = reinterpret_cast<char*>(out.data()) + done;
    const ssize_t n = ::pread(fd_, at, want, static_cast<off_t>(done));
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n < 0) throw Error("cannot read " + name_ + ": " + std::strerror(errno));
    if (n == 0) break;  // the file shrank while it was read
    check(std::string_view(at, static_cast<size_t>(n)), done);
    done += static_cast<uint64_t>(n);
  }
  if (done != size_) throw Error("cannot read " + name_ + ": it changed size while it was read");
  out.resize(done);
}

std::vector<std::byte> InputFile::read_prefix(size_t n) const {
  std::vector<std::byte> out(static_cast<size_t>(std::min<uint64_t>(n, size_)));
  size_t done = 0;
  while (done < out.size()) {
    const ssize_t got = ::pread(fd_, reinterpret_cast<char*>(out.data()) + done, out.size() - done, static_cast<off_t>(done));
    if (got < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (got < 0) throw Error("cannot read " + name_ + ": " + std::strerror(errno));
    if (got == 0) throw Error("cannot read " + name_ + ": it changed size while it was read");
    done += static_cast<size_t>(got);
  }
  return out;
}

std::vector<std::byte> InputFile::read_all() const {
  std::vector<std::byte> out;
  read_chunks(out, [](std::string_view, uint64_t) {});
  return out;
}

std::string InputFile::read_text() const {
  std::string out;
  read_chunks(out, [&](std::string_view chunk, uint64_t offset) {
    const size_t nul = chunk.find('\0');
    if (nul != std::string_view::npos)
      throw Error(name_ + " is not a text file: a NUL byte at offset " + std::to_string(offset + nul));
  });
  return out;
}

std::string read_input_file(const std::filesystem::path& path, const std::string& what, uint64_t max_bytes) {
  return InputFile(path, what, max_bytes).read_text();
}

std::vector<std::byte> read_input_bytes(const std::filesystem::path& path, const std::string& what, uint64_t max_bytes) {
  return InputFile(path, what, max_bytes).read_all();
}

std::string printable(std::string_view text) {
  std::string out;
  for (const char c : text) {
    if (static_cast<unsigned char>(c) >= 0x20 && c != 0x7f) {
      out += c;
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", static_cast<unsigned char>(c));
      out += escaped;
    }
  }
  return out;
}

std::string describe_bytes(uint64_t bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
  double value = static_cast<double>(bytes);
  int unit = 0;
  while (value >= 1024.0 && unit < 4) {
    value /= 1024.0;
    ++unit;
  }
  char text[48];
  if (unit == 0)
    std::snprintf(text, sizeof text, "%llu bytes", static_cast<unsigned long long>(bytes));
  else
    std::snprintf(text, sizeof text, value < 10.0 ? "%.1f %s" : "%.0f %s", value, units[unit]);
  return text;
}

}  // namespace sdfbench
