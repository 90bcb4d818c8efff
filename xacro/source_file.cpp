#include "xacro/source_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace lcm_control::xacro {

namespace {
constexpr std::uintmax_t kMaxSourceBytes = 64u << 20;
}  // namespace

std::string read_source_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw FileNotFound("No such file or directory: " + path);
  if (fs::is_directory(st)) throw ProcessError(fmt::format("{} is a folder, not a file", path));
  if (!fs::is_regular_file(st))
    throw ProcessError(fmt::format("{} is not a regular file (a pipe, socket or device); name the file itself", path));
  if (fs::file_size(path, ec) > kMaxSourceBytes)
    throw ProcessError(fmt::format("{} is larger than {} MB, more than any robot description", path,
                                   kMaxSourceBytes >> 20));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ProcessError(fmt::format("cannot read {}: {}", path, std::strerror(errno)));
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw ProcessError(fmt::format("cannot read {}: {}", path, std::strerror(errno)));
  return text;
}

}  // namespace lcm_control::xacro
