#include "gui/platform.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>

#ifdef _WIN32
#include <fcntl.h>
#include <io.h>
#include <sys/stat.h>

#include <cstdio>
#else
#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#endif
#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace springlab::view::platform {

#ifdef _WIN32

bool can_write_in(const std::filesystem::path& folder) {
  std::error_code error;
  return std::filesystem::is_directory(folder, error) && _waccess(folder.c_str(), 2) == 0;
}

std::string probe_writable(const std::string& path) {
  const int flags = _O_WRONLY | _O_BINARY;
  int fd = _open(path.c_str(), flags | _O_CREAT | _O_EXCL, _S_IREAD | _S_IWRITE);
  const bool made = fd >= 0;
  if (!made && errno == EEXIST) fd = _open(path.c_str(), flags);
  if (fd < 0) return std::strerror(errno);
  _close(fd);
  if (made) _unlink(path.c_str());
  return "";
}

std::optional<double> address_space_limit() {
  return std::nullopt;
}

void one_arena_under_memory_limits() {}

void set_environment_default(const char* name, const char* value) {
  if (!std::getenv(name)) _putenv_s(name, value);
}

bool standard_error_is_terminal() {
  return _isatty(_fileno(stderr)) != 0;
}

void ignore_broken_pipes() {}

#else             // POSIX

bool can_write_in(const std::filesystem::path& folder) {
  std::error_code error;
  return std::filesystem::is_directory(folder, error) && access(folder.c_str(), W_OK) == 0;
}

std::string probe_writable(const std::string& path) {
  const int flags = O_WRONLY | O_NONBLOCK | O_CLOEXEC;  // O_NONBLOCK: a FIFO does not hang here
  int fd = open(path.c_str(), flags | O_CREAT | O_EXCL, 0666);
  const bool made = fd >= 0;
  if (!made && errno == EEXIST) fd = open(path.c_str(), flags);
  if (fd < 0) return std::strerror(errno);
  close(fd);
  if (made) unlink(path.c_str());
  return "";
}

std::optional<double> address_space_limit() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return std::nullopt;
  return double(limit.rlim_cur);
}

void one_arena_under_memory_limits() {
#ifdef __GLIBC__  // other C libraries' malloc reserves no arena of address space a thread
  for (const int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit limit{};
    if (getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
      mallopt(M_ARENA_MAX, 1);
  }
#endif
}

void set_environment_default(const char* name, const char* value) {
  setenv(name, value, 0);
}

bool standard_error_is_terminal() {
  return isatty(STDERR_FILENO) == 1;
}

void ignore_broken_pipes() {
  std::signal(SIGPIPE, SIG_IGN);
}

#endif

}  // namespace springlab::view::platform
