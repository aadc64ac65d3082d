#pragma once
// Atomic output files: write to a temporary file next to the target, then rename over it, so a
// reader (or a killed run) never sees a half-written file.
#include <filesystem>
#include <span>

namespace sdfbench {

// ".<stem>.tmp<pid><ext>" in the target's directory (same file system, so rename is atomic).
std::filesystem::path temp_path_for(const std::filesystem::path& path);

// Fails early (before a long run) when `path` cannot be written: empty name, missing or
// read-only directory, or a directory in its place. `what` names the option in messages.
void check_output_path(const std::filesystem::path& path, const char* what);

// Renames `temp` over `path`; on failure removes `temp` and throws Error naming `path`.
void commit_temp_file(const std::filesystem::path& temp, const std::filesystem::path& path);

// Writes `bytes` to `path` atomically; throws Error (and leaves no temporary file) on failure.
void write_file_atomically(const std::filesystem::path& path, std::span<const std::byte> bytes);

}  // namespace sdfbench
