#include "runner/system.hpp"

#include <cmath>
#include <csignal>
#include <cstdio>
#include <string>

#if defined(_WIN32)
#ifndef NOMINMAX
#define NOMINMAX  // no min and max macros: std::min and std::max stay usable
#endif
#ifndef WIN32_LEAN_AND_MEAN
#define WIN32_LEAN_AND_MEAN
#endif
#include <windows.h>
// After windows.h, which defines the types they use.
#include <io.h>
#include <psapi.h>
#else
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace springlab::runner {

long peak_resident_mib() {
#if defined(_WIN32)
  PROCESS_MEMORY_COUNTERS counters{};
  if (GetProcessMemoryInfo(GetCurrentProcess(), &counters, sizeof counters) == 0) return 0;
  return std::lround(double(counters.PeakWorkingSetSize) / (1024.0 * 1024.0));
#else
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
#if defined(__APPLE__)
  return std::lround(double(usage.ru_maxrss) / (1024.0 * 1024.0));  // bytes on macOS
#else
  return std::lround(double(usage.ru_maxrss) / 1024.0);  // KiB on Linux and the BSDs
#endif
#endif
}

bool stderr_is_terminal() {
#if defined(_WIN32)
  return _isatty(_fileno(stderr)) != 0;
#else
  return isatty(STDERR_FILENO) == 1;
#endif
}

void write_stderr_in_handler(const char* text, unsigned long length) {
#if defined(_WIN32)
  [[maybe_unused]] const int n = _write(2, text, static_cast<unsigned>(length));
#else
  [[maybe_unused]] const ssize_t n = write(2, text, length);
#endif
}

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "INT";
    case SIGTERM:
      return "TERM";
#if !defined(_WIN32)
    case SIGHUP:
      return "HUP";
#endif
    default:
      return "(another signal)";
  }
}

void stop_on_signals(void (*on_signal)(int)) {
#if defined(_WIN32)
  // Windows has Ctrl-C and Ctrl-Break as SIGINT; std::signal resets to the default after a call.
  std::signal(SIGINT, on_signal);
#else
  // A closed pipe (springlab-run --csv - | head) is then a write error, said and exit 6, rather
  // than a death by signal with no word.
  std::signal(SIGPIPE, SIG_IGN);
  struct sigaction action {};
  action.sa_handler = on_signal;
  action.sa_flags = SA_RESTART | SA_RESETHAND;  // writes go on; a second signal kills
  sigemptyset(&action.sa_mask);
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction before {};
    sigaction(signal, nullptr, &before);
    if (before.sa_handler != SIG_IGN) sigaction(signal, &action, nullptr);  // nohup's stay ignored
  }
#endif
}

}  // namespace springlab::runner
