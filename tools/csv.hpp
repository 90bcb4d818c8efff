// One CSV file per channel for state-logger and log2csv: the header is the
// field paths of the first message; later messages fill the same columns.
#pragma once

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "tools/fields.hpp"

namespace lcm_control::tools {

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

}  // namespace lcm_control::tools
