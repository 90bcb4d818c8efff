#include "tools/csv.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace lcm_control::tools {

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
    for (size_t k = 0; k < columns_.size(); ++k) std::fprintf(f_, "%s%s", k ? "," : "", columns_[k].c_str());
    std::fputc('\n', f_);
  }
  cells_.assign(columns_.size(), std::string());
  for (const auto& f : fields) {
    const auto it = index_.find(f.path);
    if (it == index_.end())
      ++dropped_;
    else
      cells_[it->second] = f.text();
  }
  for (size_t k = 0; k < cells_.size(); ++k) std::fprintf(f_, "%s%s", k ? "," : "", cells_[k].c_str());
  std::fputc('\n', f_);
  ++rows_;
}

void CsvWriter::flush() { std::fflush(f_); }

}  // namespace lcm_control::tools
