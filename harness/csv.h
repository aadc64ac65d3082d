#pragma once
// CSV files as RFC 4180 describes them: comma-separated, fields with a comma, quote or line
// break quoted with "" doubling, one header row. Written atomically.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sdfbench {

struct CsvTable {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;  // each exactly columns.size() fields
  std::string source;                          // the file it was read from (messages), or empty

  // Index of a column; throws Error naming the file when it is missing.
  size_t column(const std::string& name) const;
  bool has_column(const std::string& name) const;
};

std::string csv_escape(const std::string& field);
std::string csv_line(const std::vector<std::string>& fields);  // with the trailing '\n'

// Throws Error (naming the file and line) for unreadable files, unterminated quotes and rows
// whose field count differs from the header's. The file is opened as every input is
// (util/input_file.h: a regular file, at most kMaxCsvBytes).
constexpr uint64_t kMaxCsvBytes = uint64_t{256} << 20;  // ~500 bytes a row: half a million rows
CsvTable read_csv(const std::filesystem::path& path);
CsvTable parse_csv(const std::string& text, const std::string& source);

void write_csv(const std::filesystem::path& path, const CsvTable& table);

}  // namespace sdfbench
