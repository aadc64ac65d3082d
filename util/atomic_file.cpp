#include "util/atomic_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>
#include <random>
#include <string>

#include "util/error.h"


namespace sdfbench {
namespace {

namespace fs = std::filesystem;

// Closes the descriptor on every path out.
class Descriptor {
 public:
  explicit Descriptor(int fd = -1) : fd_(fd) {}
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  ~Descriptor() { reset(); }
  int get() const { return fd_; }
  void reset(int fd = -1) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = fd;
  }
  // Closes now and reports whether the close succeeded (a late write error shows up here).
  bool close() {
    const int fd = fd_;
    fd_ = -1;
    return fd < 0 || ::close(fd) == 0;
  }

 private:
  int fd_;
};

fs::path directory_of(const fs::path& path) { return path.parent_path().empty() ? fs::path(".") : path.parent_path(); }

// ".<name>.<16 random hex digits>.tmp": hidden, tied to its target, and not guessable.
std::string hidden_temp_name(const std::string& target) {
  static std::random_device random;
  const unsigned long long bits = (static_cast<unsigned long long>(random()) << 32) ^ random();
  char suffix[32];
  std::snprintf(suffix, sizeof suffix, ".%016llx.tmp", bits);
  std::string name = ".";  // built step by step: GCC 12 warns falsely (-Wrestrict) on "." + string
  name += target.substr(0, 200);  // within NAME_MAX (255) for any target name
  name += suffix;
  return name;
}

// What is at `name` in `dir` when it is there and not a regular file ("a symlink", ...).
std::optional<std::string> non_regular_kind(int dir, const std::string& name) {
  struct stat st {};
  if (::fstatat(dir, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0 || S_ISREG(st.st_mode)) return std::nullopt;
  if (S_ISLNK(st.st_mode)) return "a symlink";
  if (S_ISDIR(st.st_mode)) return "a directory";
  if (S_ISFIFO(st.st_mode)) return "a FIFO";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "a device";
  if (S_ISSOCK(st.st_mode)) return "a socket";
  return "not a file";
}

// An unnamed file in `dir`, or -1 (errno set); EOPNOTSUPP (and EISDIR/EINVAL from old kernels)
// mean the file system has no O_TMPFILE.
int open_unnamed(int dir) { return ::openat(dir, ".", O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666); }
bool no_tmpfile_support(int error) { return error == EOPNOTSUPP || error == EISDIR || error == EINVAL; }

// A new file under a random hidden name, created exclusively (O_EXCL never opens an existing
// file or follows a symlink), relative to the directory's descriptor; -1 with errno set.
int open_named(int dir, const std::string& target, std::string& name) {
  for (int attempt = 0; attempt < 16; ++attempt) {
    name = hidden_temp_name(target);
    const int fd = ::openat(dir, name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  return -1;
}

// Gives the unnamed file `fd` a random hidden name in `dir`; false with errno set.
bool link_unnamed(int fd, int dir, const std::string& target, std::string& name) {
  const std::string self = "/proc/self/fd/" + std::to_string(fd);
  for (int attempt = 0; attempt < 16; ++attempt) {
    name = hidden_temp_name(target);
    // AT_EMPTY_PATH needs CAP_DAC_READ_SEARCH; /proc/self/fd works for every user where /proc is mounted.
    if (::linkat(fd, "", dir, name.c_str(), AT_EMPTY_PATH) == 0) return true;
    if (errno != EEXIST && ::linkat(AT_FDCWD, self.c_str(), dir, name.c_str(), AT_SYMLINK_FOLLOW) == 0) return true;
    if (errno != EEXIST) return false;
  }
  return false;
}

bool write_all(int fd, std::span<const std::byte> bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

// Removes the named temporary file unless the write got as far as renaming it.
struct TempName {
  int dir;
  std::string name;
  ~TempName() {
    if (!name.empty()) ::unlinkat(dir, name.c_str(), 0);
  }
};

}  // namespace

void check_output_path(const fs::path& path, const char* what) {
  if (path.empty()) throw Error(std::string(what) + ": empty file name");
  const std::string named = std::string(what) + " '" + path.string() + "'";
  if (!path.has_filename()) throw Error(named + " names a directory, not a file");
  const fs::path dir = directory_of(path);
  const Descriptor d(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (d.get() < 0) {
    if (errno == ENOENT || errno == ENOTDIR) throw Error(named + ": directory '" + dir.string() + "' does not exist");
    throw Error(named + ": cannot open directory '" + dir.string() + "': " + std::strerror(errno));
  }
  if (const auto kind = non_regular_kind(d.get(), path.filename().string()))
    throw Error(*kind == "a directory" ? named + " is a directory"
                                       : named + " exists and is not a regular file (" + *kind + "); refusing to replace it");
  // Create what the real write will (access() says yes to root even on /proc), and drop it.
  Descriptor probe(open_unnamed(d.get()));
  int error = errno;
  if (probe.get() < 0 && no_tmpfile_support(error)) {
    std::string name;
    probe.reset(open_named(d.get(), path.filename().string(), name));
    error = errno;
    if (probe.get() >= 0) ::unlinkat(d.get(), name.c_str(), 0);
  }
  if (probe.get() < 0)
    throw Error(named + ": directory '" + dir.string() + "' is not writable (" + std::strerror(error) + ")");
}

void write_file_atomically(const fs::path& path, std::span<const std::byte> bytes) {
  const std::string failed = "cannot write '" + path.string() + "'";
  auto fail = [&](int error) { return Error(failed + ": " + std::strerror(error)); };
  if (!path.has_filename()) throw Error(failed + ": it names a directory, not a file");
  const std::string target = path.filename().string();
  const Descriptor dir(::open(directory_of(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (dir.get() < 0) throw fail(errno);

  TempName temp{dir.get(), ""};
  Descriptor file(open_unnamed(dir.get()));
  if (file.get() >= 0) {
    if (!write_all(file.get(), bytes)) throw fail(errno);
    std::string name;
    if (link_unnamed(file.get(), dir.get(), target, name)) temp.name = name;
    else file.reset();  // cannot be named here (no /proc?): write it again under a name
  } else if (!no_tmpfile_support(errno)) {
    throw fail(errno);
  }
  if (file.get() < 0) {
    std::string name;
    file.reset(open_named(dir.get(), target, name));
    if (file.get() < 0) throw fail(errno);
    temp.name = name;
    if (!write_all(file.get(), bytes)) throw fail(errno);
  }
  if (!file.close()) throw fail(errno);

  // Checked again right before the rename: something may have been put there since the start.
  if (const auto kind = non_regular_kind(dir.get(), target))
    throw Error(failed + ": it exists and is not a regular file (" + *kind + "); refusing to replace it");
  if (::renameat(dir.get(), temp.name.c_str(), dir.get(), target.c_str()) != 0) throw fail(errno);
  temp.name.clear();
}

OutputLock::OutputLock(const fs::path& path, const char* what) {
  std::string name = ".";  // as in hidden_temp_name (GCC 12's false -Wrestrict)
  name += path.filename().string();
  name += ".lock";
  lock_path_ = directory_of(path) / name;
  const std::string named = std::string(what) + " '" + path.string() + "'";
  const std::string lock = "lock file '" + lock_path_.string() + "'";
  for (int attempt = 0; attempt < 16; ++attempt) {
    // O_NOFOLLOW: a symlink planted at the lock's name is refused; O_NONBLOCK: a FIFO does not hang.
    const int fd = ::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC, 0666);
    if (fd < 0) {
      if (errno == ELOOP) throw Error(named + ": " + lock + " is a symlink; refusing to follow it");
      throw Error(named + ": cannot create " + lock + ": " + std::strerror(errno));
    }
    struct stat opened {};
    if (::fstat(fd, &opened) != 0 || !S_ISREG(opened.st_mode)) {
      ::close(fd);
      throw Error(named + ": " + lock + " is not a regular file");
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      ::close(fd);
      if (error == EWOULDBLOCK)
        throw Error("another sdfbench run is writing '" + path.string() + "' (it holds '" + lock_path_.string() +
                    "'); wait for it to end or use another " + what);
      throw Error(named + ": cannot lock " + lock + ": " + std::strerror(error));
    }
    // The previous holder may have removed the file between our open and flock: then this lock
    // guards a file nobody else sees. Keep it only if the name still leads to the locked file.
    struct stat now {};
    if (::lstat(lock_path_.c_str(), &now) == 0 && now.st_dev == opened.st_dev && now.st_ino == opened.st_ino) {
      fd_ = fd;
      return;
    }
    ::close(fd);
  }
  throw Error(named + ": cannot lock " + lock + ": it keeps being replaced");
}

OutputLock::~OutputLock() {
  ::unlink(lock_path_.c_str());  // while still holding the lock, so no one locks the removed file unseen
  ::close(fd_);
}

}  // namespace sdfbench
