#include "springlab/memory_budget.hpp"

#include "springlab/errors.hpp"
#include "springlab/parallel.hpp"

// What the system says of memory: Linux's /proc and cgroups, POSIX's limits and page counts,
// Windows' own call; where a source does not exist (/proc on macOS) it limits nothing.
#if defined(_WIN32)
#ifndef NOMINMAX
#define NOMINMAX  // no min and max macros: std::min and std::max stay usable
#endif
#ifndef WIN32_LEAN_AND_MEAN
#define WIN32_LEAN_AND_MEAN
#endif
#include <windows.h>
#else
#include <pthread.h>
#include <sys/resource.h>
#include <unistd.h>
#endif

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

namespace springlab {
namespace {

constexpr double unlimited = std::numeric_limits<double>::infinity();
constexpr double kib = 1024.0, mib = 1024.0 * 1024.0;

// Springs of a rows x cols grid, family by family (scene.cpp builds them so).
double spring_count(const SceneParameters& p) {
  const double r = p.rows, c = p.cols;
  double n = 0.0;
  if (p.structural.enabled) n += r * std::max(c - 1, 0.0) + c * std::max(r - 1, 0.0);
  if (p.shear.enabled) n += 2 * std::max(r - 1, 0.0) * std::max(c - 1, 0.0);
  if (p.bend.enabled) n += r * std::max(c - 2, 0.0) + c * std::max(r - 2, 0.0);
  return n;
}

// Bytes per particle of each integrator's own buffers (2×n Vectors of 16 B a particle each):
// explicit Euler 2, symplectic Euler 1, Verlet 8 (history, estimates; on the fast path the
// springs' forces it remembers and their positions), RK4 8 (stages),
// velocity Verlet and implicit Euler about 19 (their vectors and conjugate gradients').
double integrator_bytes_per_particle(const std::string& integrator) {
  if (integrator == "explicit-euler") return 32;
  if (integrator == "symplectic-euler") return 16;
  if (integrator == "verlet") return 128;
  if (integrator == "rk4") return 128;
  if (integrator == "xpbd") return 72;  // r at a substep's start, 1/m, external forces, colours
  return 300;                           // velocity-verlet, implicit-euler
}

// A stack size as libgomp reads one: strtoul's whole number, then spaces, an optional unit (B, K,
// M or G; K if none) and spaces; bytes, or nothing when the text is not one (libgomp then keeps
// the default stack).
std::optional<double> stack_setting(const char* text) {
  if (text == nullptr) return std::nullopt;
  const auto space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  while (space(*text))
    ++text;
  if (*text == '-') return std::nullopt;  // strtoul wraps it around; libgomp refuses the result
  char* end = nullptr;
  errno = 0;
  const unsigned long value = std::strtoul(text, &end, 10);
  if (end == text || errno != 0 || value == 0) return std::nullopt;
  while (space(*end))
    ++end;
  double unit = kib;
  const std::string_view units = "bkmg";
  if (const auto i = units.find(char(std::tolower(static_cast<unsigned char>(*end))));
      *end != '\0' && i != std::string_view::npos) {
    unit = std::pow(1024.0, double(i));
    ++end;
  }
  while (space(*end))
    ++end;
  if (*end != '\0') return std::nullopt;
  return double(value) * unit;
}

// Implicit Euler's fallback, a sparse LDLT of M + hC + h²K: its fill-in grows slowly with the
// grid. Measured, max RSS of springlab-run on task5 with every k = 1e9 and m = 1e-3 (CG gives
// up, the factorisation runs), whole process: 7.8 KiB a particle at 100x100 (78 MB), 7.8 at
// 200x200 (312 MB), 9.2 at 300x300 (846 MB); 8.4 at 400x400 in issue 13. Modelled as
// 7 + 0.35 log2(n/1e4) KiB a particle on top of the rest (300x300: 850 MB estimated).
}  // namespace

double factorisation_bytes(double particles) {
  return particles * kib * (7.0 + 0.35 * std::max(0.0, std::log2(particles / 1e4)));
}

double one_thread_stack_bytes() {
  std::optional<double> bytes = stack_setting(std::getenv("OMP_STACKSIZE"));
  if (!bytes) bytes = stack_setting(std::getenv("GOMP_STACKSIZE"));
  if (!bytes) {
    bytes = 8 * mib;  // glibc's default when it cannot say
#if defined(__GLIBC__)
    pthread_attr_t attr;
    if (pthread_getattr_default_np(&attr) == 0) {
      std::size_t size = 0;
      if (pthread_attr_getstacksize(&attr, &size) == 0 && size > 0) bytes = double(size);
      pthread_attr_destroy(&attr);
    }
#endif
  }
  return *bytes + 4 * kib;
}

double thread_stack_bytes(const SceneParameters& p) {
  const double particles = double(p.rows) * double(p.cols);
  if (particles < parallel_force_particles) return 0.0;
  return (thread_count() - 1) * one_thread_stack_bytes();
}

namespace {

// "/sys/fs/cgroup/…" limit less usage for the process's own cgroup, v2 or v1.
double read_number(const std::string& path) {
  std::ifstream in(path);
  std::string text;
  if (!(in >> text) || text == "max") return unlimited;
  try {
    return std::stod(text);
  } catch (const std::exception&) {
    return unlimited;
  }
}

double cgroup_available() {
  std::ifstream groups("/proc/self/cgroup");
  std::string line;
  double best = unlimited;
  while (std::getline(groups, line)) {
    const auto first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    const std::string path = line.substr(second + 1);
    for (const std::string& dir : {path, std::string("/")}) {  // mounted as the process's root
      double limit = unlimited, used = 0.0;
      if (controllers.empty()) {  // v2
        limit = read_number("/sys/fs/cgroup" + dir + "/memory.max");
        used = read_number("/sys/fs/cgroup" + dir + "/memory.current");
      } else if (controllers.find("memory") != std::string::npos) {  // v1
        limit = read_number("/sys/fs/cgroup/memory" + dir + "/memory.limit_in_bytes");
        used = read_number("/sys/fs/cgroup/memory" + dir + "/memory.usage_in_bytes");
      }
      if (limit < 1e18) best = std::min(best, limit - (std::isfinite(used) ? used : 0.0));
    }
  }
  return best;
}

// A field of /proc/self/status or /proc/meminfo ("VmSize:  1234 kB"), bytes; 0 if absent.
double proc_field(const std::string& file, const std::string& field) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(field + ":", 0) == 0) return std::stod(line.substr(field.size() + 1)) * kib;
  return 0.0;
}

#if defined(_WIN32)
enum Resource { address_space_limit, data_limit };
double rlimit_available(Resource, const std::string&) {
  return unlimited;  // Windows has no ulimit
}

double physical_available() {
  MEMORYSTATUSEX status{};
  status.dwLength = sizeof status;
  return GlobalMemoryStatusEx(&status) != 0 ? double(status.ullAvailPhys) : unlimited;
}
#else
enum Resource { address_space_limit = RLIMIT_AS, data_limit = RLIMIT_DATA };
double rlimit_available(Resource resource, const std::string& in_use_field) {
  rlimit limit{};
  if (getrlimit(resource, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return unlimited;
  return double(limit.rlim_cur) - proc_field("/proc/self/status", in_use_field);
}

double physical_available() {
  if (const double available = proc_field("/proc/meminfo", "MemAvailable"); available > 0)
    return available;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? double(pages) * double(page) / 2 : unlimited;
}
#endif

std::string mebibytes(double bytes) {
  std::ostringstream out;
  out << std::llround(std::max(0.0, bytes) / mib);
  return out.str();
}

}  // namespace

double address_space_in_use() {
  return proc_field("/proc/self/status", "VmSize");
}

std::string mebibytes_text(double bytes) {
  return "about " + mebibytes(bytes) + " MiB";
}

MemoryLimit available_memory() {
  MemoryLimit best;
  best.bytes = physical_available();
  best.source = "physical memory";
  const auto consider = [&](double bytes, const char* source) {
    if (bytes < best.bytes) best.bytes = bytes, best.source = source;
  };
  const double address_space = rlimit_available(address_space_limit, "VmSize");
  const double data = rlimit_available(data_limit, "VmData");
  consider(address_space, "ulimit -v");
  consider(data, "ulimit -d");
  consider(cgroup_available(), "cgroup");
  // Since Linux 4.7 ulimit -d counts private writable mappings too, threads' stacks among them.
  best.mappable = std::min(address_space, data);
  best.mappable_source = address_space <= data ? "ulimit -v" : "ulimit -d";
  return best;
}

double estimated_bytes(const SceneParameters& p) {
  const double particles = double(p.rows) * double(p.cols), springs = spring_count(p);
  // The scene's particles (40 B) twice (the run's and a diagnosis' copy), the simulation's
  // buffers (56 B); each spring (40 B) with room for its list's growth; the program (8 MiB).
  // Measured (max RSS of springlab-run, task5, about 6 springs a particle): RK4 and explicit
  // Euler 0.62 KiB a particle at 200x200 (estimate 0.73), 0.52 at 1000x1000 (0.75); Verlet
  // 0.51 at 1000x1000 (0.72); velocity Verlet 0.95 at 200x200 (0.97); implicit Euler with CG
  // alone 1.17 at 300x300 on two threads (103 MiB, estimate 115; 95 MiB on one). High rather
  // than low.
  double bytes =
      8 * mib + particles * (136 + integrator_bytes_per_particle(p.integrator)) + springs * 80;
  if (p.integrator == "velocity-verlet") bytes += 16 * springs;  // its dampers
  // XPBD: each spring as a pass reads it (56 B), its λ and μ (16 B), its colour while they are
  // made (4 B).
  if (p.integrator == "xpbd") bytes += 76 * springs;
  // Implicit Euler's blocks S with their ends (32 B), a vector per spring for its gathers on two
  // threads (16 B), and each spring twice in the particles' lists (8 B).
  if (p.integrator == "implicit-euler") bytes += 56 * springs;
  return bytes;
}

void check_memory(const SceneParameters& p, const MemoryLimit& limit) {
  const std::string grid = std::to_string(p.rows) + " x " + std::to_string(p.cols);
  const double needed = estimated_bytes(p);
  if (needed > limit.bytes)
    throw InvalidParameter("rows x cols", grid,
                           "needs about " + mebibytes(needed) + " MiB with " + p.integrator +
                               "; about " + mebibytes(limit.bytes) + " MiB are free (" +
                               limit.source + "): make the grid smaller");
  const double stacks = thread_stack_bytes(p);
  if (needed + stacks > limit.mappable)
    throw InvalidParameter(
        "rows x cols", grid,
        "needs about " + mebibytes(needed) + " MiB with " + p.integrator + ", and " +
            mebibytes(stacks) + " MiB of address space for the stacks of its " +
            std::to_string(thread_count() - 1) + " other threads; about " +
            mebibytes(limit.mappable) + " MiB may be mapped (" + limit.mappable_source +
            "): make the grid smaller, or set OMP_NUM_THREADS=1");
}

void throw_out_of_memory(const SceneParameters& p, const std::string& when) {
  const MemoryLimit limit = available_memory();
  throw InvalidParameter("rows x cols", std::to_string(p.rows) + " x " + std::to_string(p.cols),
                         "the run ran out of memory " + when + " with " + p.integrator +
                             " (it needs about " + mebibytes(estimated_bytes(p)) + " MiB; about " +
                             mebibytes(limit.bytes) + " MiB are left now (" + limit.source +
                             ")): make the grid smaller");
}

}  // namespace springlab
