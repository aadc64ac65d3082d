#pragma once
// The one way sdfbench writes an output file (image, AOV, CSV, markdown, structure cache): the
// bytes go through a descriptor of a fresh file in the target's directory, an unnamed one
// (O_TMPFILE) where the file system allows it, linked under a random hidden name only when
// complete, then renamed over the target. No name is guessable, nothing is opened by name that
// another user could plant a symlink at, a killed run leaves nothing (or, without O_TMPFILE, one
// randomly named hidden file), and a reader never sees half a file. A target that exists and is
// not a regular file (symlink, FIFO, device, socket, directory) is refused, not replaced.
#include <filesystem>
#include <span>

namespace sdfbench {

// Fails early (before a long run) when `path` cannot be written: empty name, missing or
// read-only directory, or something other than a regular file in its place. Leaves nothing
// behind and follows no symlink at the target. `what` names the option in messages ("--csv").
void check_output_path(const std::filesystem::path& path, const char* what);

// Writes `bytes` to `path` atomically; throws Error naming `path` (and leaves no temporary
// file) on failure.
void write_file_atomically(const std::filesystem::path& path, std::span<const std::byte> bytes);

// An exclusive lock on an output that a run rewrites many times (a table's or sweep's --csv):
// two runs writing one file at once would each replace the other's rows, losing them silently.
// It is flock(2) on a hidden ".<name>.lock" beside the file, so the kernel releases it when its
// holder dies (a killed run blocks nobody; its empty lock file is reused and removed).
class OutputLock {
 public:
  // Throws Error naming `what` and `path` when another process holds the lock, or when the lock
  // file cannot be created or is not a regular file (a planted symlink is never followed).
  OutputLock(const std::filesystem::path& path, const char* what);
  ~OutputLock();  // removes the lock file, then releases the lock
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  std::filesystem::path lock_path_;
  int fd_ = -1;
};

}  // namespace sdfbench
