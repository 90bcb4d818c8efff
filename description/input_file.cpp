#include "description/input_file.hpp"

#include <fmt/format.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "description/robot_model.hpp"

namespace lcm_control {

namespace {
// Larger than any URDF or YAML a robot ships (the biggest real URDFs are a few MB).
constexpr off_t kMaxInputBytes = 256L * 1024 * 1024;
}  // namespace

std::string read_input_file(const std::string& path, const std::string& what, const std::string& flag) {
  if (path.empty())
    throw ModelError(fmt::format("the {} file's path is empty (give one{})", what, flag.empty() ? "" : " with " + flag));
  const std::string check = flag.empty() ? "check the path" : "check the path passed with " + flag;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw ModelError(errno == ENOENT ? fmt::format("{}: {} file not found ({})", path, what, check)
                                     : fmt::format("{}: cannot read the {} file: {}", path, what, std::strerror(errno)));
  if (S_ISDIR(st.st_mode)) throw ModelError(fmt::format("{}: is a folder, expected a {} file", path, what));
  if (!S_ISREG(st.st_mode))
    throw ModelError(fmt::format("{}: is not a regular file (a pipe, socket or device); give the {} file itself", path,
                                 what));
  if (st.st_size > kMaxInputBytes)
    throw ModelError(fmt::format("{}: {} MB is too large for a {} file (limit {} MB)", path, st.st_size >> 20, what,
                                 kMaxInputBytes >> 20));
  // O_NONBLOCK: were the file swapped for a FIFO after stat(), open() must not wait for a writer.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw ModelError(fmt::format("{}: cannot read the {} file: {}", path, what, std::strerror(errno)));
  struct stat opened {};
  if (::fstat(fd, &opened) != 0 || !S_ISREG(opened.st_mode)) {
    ::close(fd);
    throw ModelError(fmt::format("{}: is not a regular file; give the {} file itself", path, what));
  }
  std::string text;
  char buf[65536];
  while (true) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      throw ModelError(fmt::format("{}: cannot read the {} file: {}", path, what, std::strerror(err)));
    }
    if (n == 0) break;
    text.append(buf, static_cast<size_t>(n));
    if (static_cast<off_t>(text.size()) > kMaxInputBytes) {
      ::close(fd);
      throw ModelError(fmt::format("{}: too large for a {} file (limit {} MB)", path, what, kMaxInputBytes >> 20));
    }
  }
  ::close(fd);
  return text;
}

}  // namespace lcm_control
