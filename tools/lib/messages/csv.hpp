// CSV for state-logger and log2csv, and the reader for what they write: one
// file per channel whose header is the field paths of the first message; later
// messages fill the same columns. Text cells are quoted as RFC 4180 says.
#pragma once

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "tools/lib/messages/fields.hpp"

namespace lcm_control::tools {

// One RFC 4180 cell: `s` as it is, or in double quotes with its quotes doubled
// when it holds a comma, a quote, CR or LF, or starts or ends with a space.
std::string csv_quote(const std::string& s);

class CsvWriter {
 public:
  // path "-" writes to stdout. Throws std::runtime_error if the file cannot be created.
  explicit CsvWriter(const std::string& path);
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  // Writes one row (and the header before the first). Columns the first message
  // did not have are dropped and counted; missing ones are left empty.
  void write(const std::vector<Field>& fields);
  void flush();

  const std::string& path() const { return path_; }
  size_t rows() const { return rows_; }
  size_t columns() const { return columns_.size(); }
  size_t dropped_columns() const { return dropped_; }

 private:
  std::string path_;
  std::FILE* f_ = nullptr;
  bool owned_ = true;
  std::vector<std::string> columns_;
  std::map<std::string, size_t> index_;
  std::vector<std::string> cells_;
  size_t rows_ = 0, dropped_ = 0;
};

// A CSV file read back, quotes removed: every row has as many cells as the header.
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  int column(const std::string& name) const;  // -1 if the header has no such column
};

// Parses RFC 4180 text (LF or CRLF line ends; quoted cells may hold commas,
// quotes and line breaks). Throws std::runtime_error naming `source` and the
// line for an unclosed quote, a stray quote, or a row whose cell count is not the header's.
CsvTable parse_csv(const std::string& text, const std::string& source);

// parse_csv of a file; throws std::runtime_error if it cannot be read.
CsvTable read_csv(const std::string& path);

}  // namespace lcm_control::tools
