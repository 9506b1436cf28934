#include "springlab/memory_budget.hpp"

#include "springlab/errors.hpp"
#include "springlab/grid_forces.hpp"
#include "springlab/parallel.hpp"

#include <pthread.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

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
  return 300;  // velocity-verlet, implicit-euler
}

// Implicit Euler's fallback, a sparse LDLT of M + hC + h²K: its fill-in grows slowly with the
// grid. Measured, max RSS of springlab-run on task5 with every k = 1e9 and m = 1e-3 (CG gives
// up, the factorisation runs), whole process: 7.8 KiB a particle at 100x100 (78 MB), 7.8 at
// 200x200 (312 MB), 9.2 at 300x300 (846 MB); 8.4 at 400x400 in issue 13. Modelled as
// 7 + 0.35 log2(n/1e4) KiB a particle on top of the rest (300x300: 850 MB estimated).
// The address space of one more thread: its stack as glibc gives it to OpenMP's threads (the
// process's default, from `ulimit -s`; OMP_STACKSIZE when set) and a guard page. `ulimit -v`
// counts it whole, touched or not: 300x300 implicit Euler needed 12 MiB more of it on 4
// threads than on 2, 45 MiB more on 8.
double thread_stack_bytes() {
  double bytes = 8 * mib;
  pthread_attr_t attr;
  if (pthread_getattr_default_np(&attr) == 0) {
    std::size_t size = 0;
    if (pthread_attr_getstacksize(&attr, &size) == 0 && size > 0) bytes = double(size);
    pthread_attr_destroy(&attr);
  }
  if (const char* text = std::getenv("OMP_STACKSIZE"); text != nullptr && *text != '\0') {
    // OpenMP's syntax: a number, in KiB unless followed by B, K, M or G.
    char* end = nullptr;
    const double value = std::strtod(text, &end);
    const char unit = end != nullptr ? char(std::toupper(static_cast<unsigned char>(*end))) : 'K';
    const double scale = unit == 'B' ? 1.0 : unit == 'M' ? mib : unit == 'G' ? 1024 * mib : kib;
    if (std::isfinite(value) && value > 0) bytes = value * scale;
  }
  return bytes + 4 * kib;
}

}  // namespace

double factorisation_bytes(double particles) {
  return particles * kib * (7.0 + 0.35 * std::max(0.0, std::log2(particles / 1e4)));
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

double rlimit_available(int resource, const std::string& in_use_field) {
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
  MemoryLimit best{physical_available(), "physical memory"};
  const auto consider = [&](double bytes, const char* source) {
    if (bytes < best.bytes) best = {bytes, source};
  };
  consider(rlimit_available(RLIMIT_AS, "VmSize"), "ulimit -v");
  consider(rlimit_available(RLIMIT_DATA, "VmData"), "ulimit -d");
  consider(cgroup_available(), "cgroup");
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
  // Implicit Euler's blocks S with their ends (32 B), a vector per spring for its gathers on two
  // threads (16 B), and each spring twice in the particles' lists (8 B).
  if (p.integrator == "implicit-euler") bytes += 56 * springs;
  // From the fast path's size up, the kit's work runs on thread_count() threads: the others'
  // stacks (address space, which `ulimit -v` counts; little of it is ever resident).
  if (particles >= GridForces::parallel_particles)
    bytes += (thread_count() - 1) * thread_stack_bytes();
  return bytes;
}

void check_memory(const SceneParameters& p, const MemoryLimit& limit) {
  const double needed = estimated_bytes(p);
  if (needed <= limit.bytes) return;
  throw InvalidParameter("rows x cols", std::to_string(p.rows) + " x " + std::to_string(p.cols),
                         "needs about " + mebibytes(needed) + " MiB with " + p.integrator +
                             "; about " + mebibytes(limit.bytes) + " MiB are free (" +
                             limit.source + "): make the grid smaller");
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
