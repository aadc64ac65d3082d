#include "util/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include "scenes/error.h"

namespace sdfbench {

namespace fs = std::filesystem;

fs::path temp_path_for(const fs::path& path) {
  std::string name = ".";  // built step by step: GCC 12 warns falsely (-Wrestrict) on "." + string
  name += path.stem().string();
  name += ".tmp" + std::to_string(::getpid());
  name += path.extension().string();
  return path.parent_path() / name;
}

void check_output_path(const fs::path& path, const char* what) {
  if (path.empty()) throw Error(std::string(what) + ": empty file name");
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw Error(std::string(what) + " '" + path.string() + "': directory '" + dir.string() + "' does not exist");
  if (fs::is_directory(path, ec)) throw Error(std::string(what) + " '" + path.string() + "' is a directory");
  // Try the temp file the real write will use (access() says yes to root even on /proc).
  const fs::path probe = temp_path_for(path);
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) throw Error(std::string(what) + " '" + path.string() + "': directory '" + dir.string() + "' is not writable");
  ::close(fd);
  fs::remove(probe, ec);
}

void commit_temp_file(const fs::path& temp, const fs::path& path) {
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw Error("cannot write '" + path.string() + "': " + ec.message());
  }
}

void write_file_atomically(const fs::path& path, std::span<const std::byte> bytes) {
  const fs::path temp = temp_path_for(path);
  std::FILE* file = std::fopen(temp.c_str(), "wb");
  if (!file) throw Error("cannot write '" + path.string() + "': " + std::strerror(errno));
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
  const int write_errno = errno;
  const bool closed = std::fclose(file) == 0;
  if (!written || !closed) {
    std::error_code ec;
    fs::remove(temp, ec);
    throw Error("cannot write '" + path.string() + "': " + std::strerror(written ? errno : write_errno));
  }
  commit_temp_file(temp, path);
}

}  // namespace sdfbench
