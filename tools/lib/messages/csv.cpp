#include "tools/lib/messages/csv.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace lcm_control::tools {

std::string csv_quote(const std::string& s) {
  const bool needs = s.find_first_of(",\"\r\n") != std::string::npos ||
                     (!s.empty() && (s.front() == ' ' || s.back() == ' '));
  if (!needs) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

CsvWriter::CsvWriter(const std::string& path) : path_(path) {
  if (path == "-") {
    f_ = stdout;
    owned_ = false;
    return;
  }
  f_ = std::fopen(path.c_str(), "w");
  if (!f_) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
}

CsvWriter::~CsvWriter() {
  if (!f_) return;
  if (owned_)
    std::fclose(f_);
  else
    std::fflush(f_);
}

void CsvWriter::write(const std::vector<Field>& fields) {
  if (columns_.empty()) {
    for (const auto& f : fields) {
      index_[f.path] = columns_.size();
      columns_.push_back(f.path);
    }
    for (size_t k = 0; k < columns_.size(); ++k)
      std::fprintf(f_, "%s%s", k ? "," : "", csv_quote(columns_[k]).c_str());
    std::fputc('\n', f_);
  }
  cells_.assign(columns_.size(), std::string());
  for (const auto& f : fields) {
    const auto it = index_.find(f.path);
    if (it == index_.end())
      ++dropped_;
    else
      cells_[it->second] = csv_quote(f.text());
  }
  for (size_t k = 0; k < cells_.size(); ++k) std::fprintf(f_, "%s%s", k ? "," : "", cells_[k].c_str());
  std::fputc('\n', f_);
  ++rows_;
}

void CsvWriter::flush() { std::fflush(f_); }

int CsvTable::column(const std::string& name) const {
  for (size_t k = 0; k < header.size(); ++k)
    if (header[k] == name) return int(k);
  return -1;
}

namespace {

// Length of the line end at text[i]: 2 for CRLF, 1 for LF (or a CR ending the text), 0 for none.
size_t line_end(const std::string& text, size_t i) {
  if (i >= text.size()) return 0;
  if (text[i] == '\n') return 1;
  if (text[i] == '\r') return i + 1 == text.size() ? 1 : text[i + 1] == '\n' ? 2 : 0;
  return 0;
}

}  // namespace

CsvTable parse_csv(const std::string& text, const std::string& source) {
  auto fail = [&](size_t line, const std::string& what) {
    return std::runtime_error(fmt::format("{}:{}: {}", source, line, what));
  };
  CsvTable table;
  bool have_header = false;
  size_t i = 0, line = 1;
  const size_t n = text.size();
  while (i < n) {
    if (const size_t e = line_end(text, i)) {  // a blank line is not a row
      i += e;
      ++line;
      continue;
    }
    const size_t row_line = line;
    std::vector<std::string> row;
    for (;;) {
      std::string cell;
      if (text[i] == '"') {
        const size_t open_line = line;
        for (++i;; ++i) {
          if (i >= n)
            throw fail(open_line, fmt::format("column {}: the quoted cell is never closed; end it with \" and double "
                                              "every quote inside it",
                                              row.size() + 1));
          if (text[i] == '"') {
            if (i + 1 < n && text[i + 1] == '"') {
              cell += '"';
              ++i;
              continue;
            }
            ++i;
            break;
          }
          if (text[i] == '\n') ++line;
          cell += text[i];
        }
        if (i < n && text[i] != ',' && !line_end(text, i))
          throw fail(line, fmt::format("column {}: text after the closing quote; quote the whole cell and double "
                                       "every quote inside it",
                                       row.size() + 1));
      } else {
        for (; i < n && text[i] != ',' && !line_end(text, i); ++i) {
          if (text[i] == '"')
            throw fail(line, fmt::format("column {}: a quote in an unquoted cell; quote the whole cell and double "
                                         "every quote inside it",
                                         row.size() + 1));
          cell += text[i];
        }
      }
      row.push_back(std::move(cell));
      if (i < n && text[i] == ',') {
        ++i;
        if (i < n && !line_end(text, i)) continue;
        row.emplace_back();
      }
      if (const size_t e = line_end(text, i)) {
        i += e;
        ++line;
      }
      break;
    }
    if (!have_header) {
      table.header = std::move(row);
      have_header = true;
    } else if (row.size() != table.header.size()) {
      throw fail(row_line, fmt::format("{} cells where the header has {}; a cell holding a comma must be quoted",
                                       row.size(), table.header.size()));
    } else {
      table.rows.push_back(std::move(row));
    }
  }
  return table;
}

CsvTable read_csv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_csv(ss.str(), path);
}

}  // namespace lcm_control::tools
