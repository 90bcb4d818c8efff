#include "tools/lib/process/process_c.h"

#include <cerrno>
#include <exception>
#include <string>
#include <vector>

#include "tools/lib/process/process.hpp"

using namespace lcm_control::tools;

int lcm_control_start_process(const char* const* argv, int output_fd, const int* cpus, int n_cpus, int own_group) {
  try {
    std::vector<std::string> args;
    for (const char* const* a = argv; a && *a; ++a) args.emplace_back(*a);
    ProcessOptions options{own_group != 0, true, {}};
    if (cpus && n_cpus > 0) options.cpus.assign(cpus, cpus + n_cpus);
    return start_process(args, environment_with({}), output_fd, options);
  } catch (const std::exception&) {
    return -1;
  }
}

void lcm_control_signal_process(int pid, int sig) { signal_process(pid, sig); }

int lcm_control_reap_process(int pid, int block, int* code, double* user_s, double* system_s, long* maxrss_kb) {
  rusage usage{};
  errno = 0;
  const std::optional<int> c = reap_process(pid, block != 0, &usage);
  if (!c) return errno == ECHILD ? -1 : 0;
  if (code) *code = *c;
  if (user_s) *user_s = double(usage.ru_utime.tv_sec) + double(usage.ru_utime.tv_usec) * 1e-6;
  if (system_s) *system_s = double(usage.ru_stime.tv_sec) + double(usage.ru_stime.tv_usec) * 1e-6;
  if (maxrss_kb) *maxrss_kb = usage.ru_maxrss;
  return 1;
}
