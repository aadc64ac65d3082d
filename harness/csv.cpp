#include "harness/csv.h"

#include <algorithm>

#include "util/atomic_file.h"
#include "util/error.h"
#include "util/input_file.h"

namespace sdfbench {

size_t CsvTable::column(const std::string& name) const {
  for (size_t i = 0; i < columns.size(); ++i)
    if (columns[i] == name) return i;
  throw Error((source.empty() ? "CSV" : "'" + source + "'") + " has no column '" + name + "'");
}

bool CsvTable::has_column(const std::string& name) const {
  return std::find(columns.begin(), columns.end(), name) != columns.end();
}

std::string csv_escape(const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string quoted = "\"";
  for (char c : field) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  quoted += '"';
  return quoted;
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string line;
  for (size_t i = 0; i < fields.size(); ++i) {
    if (i) line += ',';
    line += csv_escape(fields[i]);
  }
  line += '\n';
  return line;
}

CsvTable parse_csv(const std::string& text, const std::string& source) {
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> record;
  std::string field;
  bool quoted = false, field_started = false;
  size_t line = 1, record_line = 1;
  auto end_field = [&] {
    record.push_back(std::move(field));
    field.clear();
    field_started = false;
  };
  // A UTF-8 byte-order mark (spreadsheets write one) is not part of the first column's name.
  const size_t start = text.starts_with("\xef\xbb\xbf") ? 3 : 0;
  for (size_t i = start; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        line += c == '\n';
        field += c;
      }
    } else if (c == '"' && !field_started) {
      quoted = field_started = true;
    } else if (c == ',') {
      end_field();
    } else if (c == '\n' || c == '\r') {
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      end_field();
      records.push_back(std::move(record));
      record.clear();
      record_line = ++line;
    } else if (c == '"') {
      throw Error(source + ":" + std::to_string(line) + ": stray quote inside an unquoted field");
    } else {
      field += c;
      field_started = true;
    }
  }
  if (quoted) throw Error(source + ":" + std::to_string(record_line) + ": unterminated quoted field");
  if (field_started || !record.empty()) {
    end_field();
    records.push_back(std::move(record));
  }
  if (records.empty()) throw Error(source + ": empty CSV file (no header row)");
  CsvTable table;
  table.source = source;
  table.columns = std::move(records.front());
  for (size_t r = 1; r < records.size(); ++r) {
    if (records[r].size() == 1 && records[r][0].empty()) continue;  // blank line
    if (records[r].size() != table.columns.size())
      throw Error(source + ": row " + std::to_string(r) + " has " + std::to_string(records[r].size()) + " fields, the header " +
                  std::to_string(table.columns.size()));
    table.rows.push_back(std::move(records[r]));
  }
  return table;
}

CsvTable read_csv(const std::filesystem::path& path) {
  return parse_csv(read_input_file(path, "CSV", kMaxCsvBytes), path.string());
}

void write_csv(const std::filesystem::path& path, const CsvTable& table) {
  std::string text = csv_line(table.columns);
  for (const auto& row : table.rows) text += csv_line(row);
  write_file_atomically(path, std::as_bytes(std::span(text.data(), text.size())));
}

}  // namespace sdfbench
