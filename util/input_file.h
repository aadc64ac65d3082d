#pragma once
// The one way sdfbench opens an input file (scene, mesh, texture, cache, CSV): it must be a
// regular file (a FIFO, device or directory would hang or never end), checked on the opened
// descriptor itself, and no larger than the caller's limit, checked before anything is read.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sdfbench {

// The whole file. `what` names it in messages ("scene file", "OBJ", "SDF cache"); a file over
// `max_bytes` is refused (Error naming the file, its size and the limit) before it is read.
std::string read_input_file(const std::filesystem::path& path, const std::string& what, uint64_t max_bytes);
std::vector<std::byte> read_input_bytes(const std::filesystem::path& path, const std::string& what, uint64_t max_bytes);

// Byte counts for messages: "1.5 GiB", "300 MiB", "12 KiB", "17 bytes".
std::string describe_bytes(uint64_t bytes);

}  // namespace sdfbench
