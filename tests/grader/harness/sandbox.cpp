#include "sandbox.hpp"

#include "springlab/parallel.hpp"

#include <fcntl.h>
#include <linux/landlock.h>
#include <seccomp.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <fstream>
#include <memory>
#include <sstream>

namespace springlab::grading {
namespace {

// TCGETS2, the termios2 read of a terminal's settings: _IOR('T', 0x2A, struct termios2), the
// struct being 44 bytes. Written out: <asm/termbits.h>, which defines it, clashes with <termios.h>.
constexpr unsigned long tcgets2 = (2UL << 30) | (44UL << 16) | ('T' << 8) | 0x2A;
static_assert(tcgets2 == 0x802C542AUL);

// What a Catch2 test, Eigen, the C++ runtime and the sanitizers' runtime use while running and
// while reporting an error (found with strace on every kit test, plain and sanitized).
constexpr const char* allowed[] = {
    "read",          "readv",
    "pread64",       "write",
    "writev",        "close",
    "lseek",         "fstat",
    "newfstatat",    "stat",
    "lstat",         "statx",
    "access",        "faccessat",
    "faccessat2",    "readlink",
    "readlinkat",    "getcwd",
    "getdents64",    "fcntl",
    "dup",           "dup2",
    "dup3",          "mmap",
    "munmap",        "mprotect",
    "mremap",        "brk",
    "madvise",       "mincore",
    "rt_sigaction",  "rt_sigprocmask",
    "rt_sigreturn",  "sigaltstack",
    "getpid",        "gettid",
    "getppid",       "getuid",
    "geteuid",       "getgid",
    "getegid",       "getrlimit",
    "getrusage",     "sched_getaffinity",
    "sched_yield",   "uname",
    "sysinfo",       "exit",
    "exit_group",    "futex",
    "clock_gettime", "clock_getres",
    "gettimeofday",  "time",
    "nanosleep",     "clock_nanosleep",
    "getrandom",     "prctl",
    "arch_prctl",    "set_robust_list",
    "rseq",          "restart_syscall",
    "poll",          "ppoll",
    "pipe",          "pipe2",
    "seccomp"};  // more filters can only forbid more: forbid_new_code() adds one

void (*report_forbidden)(long) = nullptr;

void report_and_end(int, siginfo_t* info, void*) {
  if (report_forbidden != nullptr) report_forbidden(info->si_syscall);
  _exit(0);
}

using Filter = std::unique_ptr<void, decltype(&seccomp_release)>;

bool add(const Filter& filter, uint32_t action, const char* name, unsigned count = 0,
         scmp_arg_cmp first = {}, scmp_arg_cmp second = {}) {
  const int call = seccomp_syscall_resolve_name(name);
  if (call == __NR_SCMP_ERROR) return true;  // not a system call on this architecture
  if (count == 0) return seccomp_rule_add(filter.get(), action, call, 0) == 0;
  if (count == 1) return seccomp_rule_add(filter.get(), action, call, 1, first) == 0;
  return seccomp_rule_add(filter.get(), action, call, 2, first, second) == 0;
}

bool load(const Filter& filter) {
  if (!filter) return false;
  const int error = seccomp_load(filter.get());
  if (error != 0) errno = -error;
  return error == 0;
}

}  // namespace

bool forbid_what_tests_never_need(void (*on_forbidden)(long number)) {
  // Starting a thread is forbidden below: the kit's own code (parallel.hpp) must stay on this
  // one, whatever the size of a scene a test builds.
  springlab::set_thread_count(1);
  report_forbidden = on_forbidden;
  struct sigaction action = {};
  action.sa_sigaction = report_and_end;
  action.sa_flags = SA_SIGINFO;
  sigaction(SIGSYS, &action, nullptr);

  // Two filters: the kernel applies the stricter answer of the two. The first lets everything
  // through but turns an open for writing into EACCES and traps the descriptor settings that
  // make the kernel signal someone; the second allows only the list above (opening files of any
  // kind included) and traps the rest.
  const Filter writes(seccomp_init(SCMP_ACT_ALLOW), seccomp_release);
  const uint32_t refuse = SCMP_ACT_ERRNO(EACCES);
  bool ok = bool(writes);
  for (const int flag : {O_WRONLY, O_RDWR})
    for (const char* call : {"open", "openat"}) {
      const unsigned flags_arg = call[4] == 'a' ? 2 : 1;
      ok = ok && add(writes, refuse, call, 1,
                     SCMP_CMP(flags_arg, SCMP_CMP_MASKED_EQ, O_ACCMODE, scmp_datum_t(flag)));
    }
  for (const int flag : {O_CREAT, O_TRUNC, O_APPEND})
    for (const char* call : {"open", "openat"}) {
      const unsigned flags_arg = call[4] == 'a' ? 2 : 1;
      ok = ok &&
           add(writes, refuse, call, 1,
               SCMP_CMP(flags_arg, SCMP_CMP_MASKED_EQ, scmp_datum_t(flag), scmp_datum_t(flag)));
    }
  ok = ok && add(writes, refuse, "creat") && add(writes, refuse, "openat2");
  // A descriptor's owner gets a signal from the kernel when I/O is possible on it (SIGIO, or the
  // one F_SETSIG chooses): owned by another process, such as the harness, or by a process group,
  // any pipe the worker makes would signal it. So fcntl may neither name an owner nor switch on
  // O_ASYNC (fcntl64 is the same call on 32-bit systems).
  for (const char* call : {"fcntl", "fcntl64"}) {
    for (const int command : {F_SETOWN, F_SETOWN_EX, F_SETSIG})
      ok = ok && add(writes, SCMP_ACT_TRAP, call, 1, SCMP_A1(SCMP_CMP_EQ, scmp_datum_t(command)));
    const auto async = scmp_datum_t(O_ASYNC);
    ok = ok && add(writes, SCMP_ACT_TRAP, call, 2, SCMP_A1(SCMP_CMP_EQ, scmp_datum_t(F_SETFL)),
                   SCMP_A2(SCMP_CMP_MASKED_EQ, async, async));
  }

  const Filter calls(seccomp_init(SCMP_ACT_TRAP), seccomp_release);
  ok = ok && bool(calls);
  for (const char* name : allowed)
    ok = ok && add(calls, SCMP_ACT_ALLOW, name);
  ok = ok && add(calls, SCMP_ACT_ALLOW, "open") && add(calls, SCMP_ACT_ALLOW, "openat");
  // Signals to itself only (abort() and the sanitizers raise SIGABRT that way).
  const auto self = scmp_datum_t(getpid());
  ok = ok && add(calls, SCMP_ACT_ALLOW, "kill", 1, SCMP_A0(SCMP_CMP_EQ, self)) &&
       add(calls, SCMP_ACT_ALLOW, "tgkill", 1, SCMP_A0(SCMP_CMP_EQ, self)) &&
       add(calls, SCMP_ACT_ALLOW, "tkill", 1, SCMP_A0(SCMP_CMP_EQ, self));
  // isatty() only: other terminal requests could type into the grader's terminal. glibc 2.42
  // (Debian sid, Ubuntu 26.04) asks with TCGETS2, the termios2 form of the same read: without it
  // every test there stopped on "ioctl".
  ok = ok && add(calls, SCMP_ACT_ALLOW, "ioctl", 1, SCMP_A1(SCMP_CMP_EQ, TCGETS));
  ok = ok && add(calls, SCMP_ACT_ALLOW, "ioctl", 1, SCMP_A1(SCMP_CMP_EQ, tcgets2));
  // Limits may be read, never raised (a process running as root could raise them).
  ok = ok && add(calls, SCMP_ACT_ALLOW, "prlimit64", 1, SCMP_A2(SCMP_CMP_EQ, 0));
  if (!ok) return false;
  return load(writes) && load(calls);
}

bool forbid_new_code() {
  const Filter filter(seccomp_init(SCMP_ACT_ALLOW), seccomp_release);
  const auto exec = scmp_datum_t(PROT_EXEC);
  return add(filter, SCMP_ACT_TRAP, "mmap", 1, SCMP_A2(SCMP_CMP_MASKED_EQ, exec, exec)) &&
         add(filter, SCMP_ACT_TRAP, "mprotect", 1, SCMP_A2(SCMP_CMP_MASKED_EQ, exec, exec)) &&
         add(filter, SCMP_ACT_TRAP, "pkey_mprotect", 1, SCMP_A2(SCMP_CMP_MASKED_EQ, exec, exec)) &&
         load(filter);
}

}  // namespace springlab::grading

namespace springlab::grading {
namespace {

// Landlock's rights on files, as far as this kernel's version of it knows them (the later ones by
// their numbers: Debian 12's headers predate them).
std::uint64_t handled_rights(long abi) {
  std::uint64_t rights = (LANDLOCK_ACCESS_FS_MAKE_SYM << 1) - 1;  // version 1: bits 0-12
  if (abi >= 2) rights |= LANDLOCK_ACCESS_FS_REFER;
  if (abi >= 3) rights |= 1ULL << 14;  // truncate
  if (abi >= 5) rights |= 1ULL << 15;  // ioctl on devices
  return rights;
}

bool allow(int ruleset, const std::string& path, std::uint64_t rights) {
  const int fd = ::open(path.c_str(), O_PATH | O_CLOEXEC);
  if (fd < 0) return errno == ENOENT;  // a folder this system does not have
  struct stat info = {};
  ::fstat(fd, &info);
  landlock_path_beneath_attr rule{};
  rule.allowed_access = S_ISDIR(info.st_mode)
                            ? rights
                            : rights & (LANDLOCK_ACCESS_FS_EXECUTE | LANDLOCK_ACCESS_FS_READ_FILE);
  rule.parent_fd = fd;
  const long done = ::syscall(SYS_landlock_add_rule, ruleset, LANDLOCK_RULE_PATH_BENEATH, &rule, 0);
  ::close(fd);
  return done == 0;
}

bool is_within(const std::string& path, const std::string& folder) {
  return path.compare(0, folder.size(), folder) == 0 &&
         (path.size() == folder.size() || path[folder.size()] == '/');
}

}  // namespace

bool read_only_what_tests_need(const std::string& program, const std::string& library) {
  const long abi =
      ::syscall(SYS_landlock_create_ruleset, nullptr, 0, LANDLOCK_CREATE_RULESET_VERSION);
  if (abi < 1) return false;
  landlock_ruleset_attr attributes{};
  attributes.handled_access_fs = handled_rights(abi);
  const int ruleset =
      int(::syscall(SYS_landlock_create_ruleset, &attributes, sizeof attributes, 0));
  if (ruleset < 0) return false;
  const std::uint64_t read =
      LANDLOCK_ACCESS_FS_EXECUTE | LANDLOCK_ACCESS_FS_READ_FILE | LANDLOCK_ACCESS_FS_READ_DIR;
  bool ok = true;
  for (const std::string folder : {"/usr", "/lib", "/lib64", "/etc", "/proc", "/sys"})
    ok = ok && allow(ruleset, folder, read);
  for (const std::string& file :
       {std::string("/dev/null"), std::string("/dev/urandom"), program, library})
    ok = ok && allow(ruleset, file, read);
  ok = ok && ::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) == 0 &&
       ::syscall(SYS_landlock_restrict_self, ruleset, 0) == 0;
  ::close(ruleset);
  return ok;
}

std::string foreign_code(const std::string& program, const std::string& library) {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line)) {
    std::istringstream fields(line);
    std::string range, permissions, offset, device, inode, path;
    fields >> range >> permissions >> offset >> device >> inode;
    std::getline(fields >> std::ws, path);
    if (permissions.size() < 3 || permissions[2] != 'x') continue;
    const bool system = is_within(path, "/usr") || is_within(path, "/lib") ||
                        is_within(path, "/lib64") || path == "[vdso]" || path == "[vsyscall]";
    if (!system && path != program && path != library)
      return path.empty() ? "memory made executable at " + range : path;
  }
  return "";
}

}  // namespace springlab::grading
