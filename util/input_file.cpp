#include "util/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "scenes/error.h"

namespace sdfbench {

namespace {

// Closes the descriptor on every path out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

template <class Buffer>
Buffer read_all(const std::filesystem::path& path, const std::string& what, uint64_t max_bytes) {
  const std::string name = what + " '" + path.string() + "'";
  // O_NONBLOCK: opening a FIFO must not wait for a writer; the type check below refuses it.
  const Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
  if (file.fd < 0) {
    if (errno == ENOENT) throw Error(name + " does not exist");
    throw Error("cannot open " + name + ": " + std::strerror(errno));
  }
  struct stat st {};
  if (::fstat(file.fd, &st) != 0) throw Error("cannot read " + name + ": " + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw Error(name + " is a directory, not a file");
  if (!S_ISREG(st.st_mode)) throw Error(name + " is not a regular file (a FIFO, socket or device)");
  const uint64_t size = static_cast<uint64_t>(st.st_size);
  if (size > max_bytes)
    throw Error(name + " is " + describe_bytes(size) + ", more than the limit for a " + what + " (" +
                describe_bytes(max_bytes) + ")");
  Buffer buffer(size, typename Buffer::value_type{});
  uint64_t done = 0;
  while (done < size) {
    const ssize_t n = ::read(file.fd, reinterpret_cast<char*>(buffer.data()) + done, size - done);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n < 0) throw Error("cannot read " + name + ": " + std::strerror(errno));
    if (n == 0) break;  // the file shrank while it was read
    done += static_cast<uint64_t>(n);
  }
  if (done != size) throw Error("cannot read " + name + ": it changed size while it was read");
  return buffer;
}

}  // namespace

std::string read_input_file(const std::filesystem::path& path, const std::string& what, uint64_t max_bytes) {
  return read_all<std::string>(path, what, max_bytes);
}

std::vector<std::byte> read_input_bytes(const std::filesystem::path& path, const std::string& what, uint64_t max_bytes) {
  return read_all<std::vector<std::byte>>(path, what, max_bytes);
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
