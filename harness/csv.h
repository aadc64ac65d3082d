#pragma once
// CSV files as RFC 4180 describes them: comma-separated, fields with a comma, quote or line
// break quoted with "" doubling, one header row. Written atomically.
#include <filesystem>
#include <string>
#include <vector>

namespace sdfbench {

struct CsvTable {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;  // each exactly columns.size() fields

  // Index of a column; throws Error naming the file's columns when it is missing.
  size_t column(const std::string& name) const;
};

std::string csv_escape(const std::string& field);
std::string csv_line(const std::vector<std::string>& fields);  // with the trailing '\n'

// Throws Error (naming the file and line) for unreadable files, unterminated quotes and rows
// whose field count differs from the header's.
CsvTable read_csv(const std::filesystem::path& path);
CsvTable parse_csv(const std::string& text, const std::string& source);

void write_csv(const std::filesystem::path& path, const CsvTable& table);

}  // namespace sdfbench
