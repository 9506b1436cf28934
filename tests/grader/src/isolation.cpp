#include "isolation.hpp"

#include "policy.hpp"
#include "process.hpp"

#include <fcntl.h>
#include <pwd.h>
#include <sched.h>
#include <seccomp.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <system_error>

namespace springlab::grader {
namespace {

constexpr uid_t nobody = 65534;  // nobody and nogroup on Debian and Ubuntu

std::string find_program(const std::string& name) {
  for (const char* folder : {"/usr/bin", "/bin", "/usr/sbin", "/usr/local/bin"})
    if (const fs::path p = fs::path(folder) / name; ::access(p.c_str(), X_OK) == 0) return p;
  return "";
}

// The last line of what a failed probe printed: bubblewrap's own reason.
std::string last_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
    text.pop_back();
  const auto at = text.rfind('\n');
  return at == std::string::npos ? text : text.substr(at + 1);
}

using Context = std::unique_ptr<void, decltype(&seccomp_release)>;

// Makes the call `name` fail with `error` when every comparison holds (a call this architecture
// does not have is left out).
bool refuse(const Context& filter, const char* name, std::vector<scmp_arg_cmp> compare = {},
            int error = EPERM) {
  const int call = seccomp_syscall_resolve_name(name);
  if (call == __NR_SCMP_ERROR) return true;
  return seccomp_rule_add_array(filter.get(), SCMP_ACT_ERRNO(std::uint32_t(error)), call,
                                unsigned(compare.size()), compare.data()) == 0;
}

// The program libseccomp made of `filter` (its version 2.5, Debian 12's, writes it to a
// descriptor only).
std::vector<sock_filter> program_of(const Context& filter) {
  const int fd = ::memfd_create("springlab-filter", MFD_CLOEXEC);
  std::vector<sock_filter> program;
  if (fd >= 0 && seccomp_export_bpf(filter.get(), fd) == 0) {
    program.resize(std::size_t(::lseek(fd, 0, SEEK_END)) / sizeof(sock_filter));
    const auto size = program.size() * sizeof(sock_filter);
    if (::pread(fd, program.data(), size, 0) != ssize_t(size)) program.clear();
  }
  if (fd >= 0) ::close(fd);
  if (program.empty()) throw std::runtime_error("cannot make the builds' system-call filter");
  return program;
}

// Signals, to the command's own process group only (kill(0, ...)) or the threads of its first
// process (tgkill(own group, ...), what raise() and abort() use there): a filter's rules see
// numbers, not processes, and these two name the command's own whatever number it has, since
// the group can neither be left (setsid, setpgid) nor outlived by its id. Any other pid, a
// descriptor for one, or the kernel signalling a descriptor's owner is refused.
bool refuse_signals(const Context& f) {
  const auto group = scmp_datum_t(SystemCallFilter::own_group);
  bool ok = refuse(f, "kill", {SCMP_A0(SCMP_CMP_NE, 0)});
  for (const char* name : {"tgkill", "rt_sigqueueinfo", "rt_tgsigqueueinfo"})
    ok = ok && refuse(f, name, {SCMP_A0(SCMP_CMP_NE, group)});
  for (const char* name :
       {"tkill", "pidfd_open", "pidfd_send_signal", "pidfd_getfd", "setsid", "setpgid"})
    ok = ok && refuse(f, name);
  for (const char* call : {"fcntl", "fcntl64"}) {
    for (const int command : {F_SETOWN, F_SETOWN_EX, F_SETSIG})
      ok = ok && refuse(f, call, {SCMP_A1(SCMP_CMP_EQ, scmp_datum_t(command))});
    const auto async = scmp_datum_t(O_ASYNC);
    ok = ok && refuse(f, call,
                      {SCMP_A1(SCMP_CMP_EQ, scmp_datum_t(F_SETFL)),
                       SCMP_A2(SCMP_CMP_MASKED_EQ, async, async)});
  }
  return ok;
}

// Everything else by which a process reaches another of the same user: tracing it, its memory,
// its limits and scheduling (prlimit64, setpriority, ... on any but itself), the terminal's input;
// and the network, and namespaces where a kernel would still give some.
bool refuse_reaching_others(const Context& f) {
  bool ok = true;
  for (const char* name :
       {"ptrace", "process_vm_readv", "process_vm_writev", "process_madvise", "kcmp",
        "migrate_pages", "move_pages", "socket", "io_uring_setup", "bpf", "perf_event_open",
        "userfaultfd", "add_key", "request_key", "keyctl", "unshare", "setns"})
    ok = ok && refuse(f, name);
  for (const char* name :
       {"prlimit64", "sched_setaffinity", "sched_setscheduler", "sched_setparam", "sched_setattr"})
    ok = ok && refuse(f, name, {SCMP_A0(SCMP_CMP_NE, 0)});
  for (const char* name : {"setpriority", "ioprio_set"})  // (which, who): 1 is the process itself
    ok = ok &&
         refuse(f, name, {SCMP_A0(SCMP_CMP_NE, scmp_datum_t(name[0] == 's' ? PRIO_PROCESS : 1))}) &&
         refuse(f, name, {SCMP_A1(SCMP_CMP_NE, 0)});
  ok = ok && refuse(f, "ioctl", {SCMP_A1(SCMP_CMP_MASKED_EQ, 0xffffffff, TIOCSTI)});
  // clone3's flags are out of a filter's sight: without it the C library uses clone.
  ok = ok && refuse(f, "clone3", {}, ENOSYS);
  for (const auto flag : {CLONE_NEWNS, CLONE_NEWUSER, CLONE_NEWPID, CLONE_NEWNET, CLONE_NEWIPC,
                          CLONE_NEWUTS, CLONE_NEWCGROUP})
    ok = ok &&
         refuse(f, "clone", {SCMP_A0(SCMP_CMP_MASKED_EQ, scmp_datum_t(flag), scmp_datum_t(flag))});
  return ok;
}

// Why the reserved users cannot be users apart here ("" when they can): one of them has an
// account or runs a process on this machine, or this system cannot switch to them (a user
// namespace that maps root alone).
std::string why_users_not_apart() {
  const uid_t first = Isolation::users_from, last = first + ProcessPool::users_apart - 1;
  const auto reserved = [&](uid_t user) { return user >= first && user <= last; };
  std::string why;
  ::setpwent();
  for (const passwd* p = ::getpwent(); p != nullptr && why.empty(); p = ::getpwent())
    if (reserved(p->pw_uid))
      why = "the user " + std::string(p->pw_name) + " (" + std::to_string(p->pw_uid) + ") exists";
  ::endpwent();
  std::error_code error;
  for (const auto& entry : fs::directory_iterator("/proc", error)) {
    std::ifstream status(entry.path() / "status");
    for (std::string line; why.empty() && std::getline(status, line);) {
      if (line.rfind("Uid:", 0) != 0) continue;
      std::istringstream ids(line.substr(4));
      for (uid_t user = 0; why.empty() && ids >> user;)
        if (reserved(user))
          why = "process " + entry.path().filename().string() + " runs as user " +
                std::to_string(user);
    }
  }
  if (!why.empty()) return why;
  const pid_t child = ::fork();
  if (child == 0)
    ::_exit(::setresgid(nobody, nobody, nobody) == 0 && ::setresuid(first, first, first) == 0 ? 0
                                                                                              : 1);
  int status = 0;
  if (child < 0 || ::waitpid(child, &status, 0) != child || !WIFEXITED(status) ||
      WEXITSTATUS(status) != 0)
    return "this system cannot switch to the user " + std::to_string(first);
  return "";
}

}  // namespace

std::shared_ptr<const SystemCallFilter> Isolation::build_filter() {
  const Context filter(seccomp_init(SCMP_ACT_ALLOW), seccomp_release);
  if (!filter || !refuse_signals(filter) || !refuse_reaching_others(filter))
    throw std::runtime_error("cannot make the builds' system-call filter");
  auto made = std::make_shared<SystemCallFilter>();
  made->program = program_of(filter);
  return made;
}

Isolation Isolation::without_namespaces(const std::string& why) {
  Isolation i;
  i.why_not_ = why;
  i.run_as_ = ::geteuid() == 0 ? nobody : uid_t(-1);
  i.filter_ = build_filter();
  if (::geteuid() == 0) {
    i.why_not_apart_ = why_users_not_apart();
    i.users_apart_ = i.why_not_apart_.empty();
  }
  return i;
}

Isolation Isolation::probe(std::vector<fs::path> hide) {
  Isolation i = without_namespaces("");
  i.hide_ = std::move(hide);
  i.bwrap_ = find_program("bwrap");
  i.setpriv_ = find_program("setpriv");
  if (i.bwrap_.empty()) {
    i.why_not_ = "bubblewrap (bwrap) is not installed; ./lab setup installs it";
    return i;
  }
  if (::geteuid() == 0 && i.setpriv_.empty()) {
    i.why_not_ = "setpriv (util-linux) is not installed, and commands must not run as root";
    return i;
  }
  // The system's programs and libraries, read-only; on a merged-/usr system /bin, /lib, ... are
  // links into /usr, and stay links.
  i.system_ = {"--ro-bind", "/usr", "/usr"};
  for (const char* top : {"/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32"}) {
    std::error_code error;
    const auto status = fs::symlink_status(top, error);
    if (fs::is_symlink(status)) {
      i.system_.insert(i.system_.end(), {"--symlink", fs::read_symlink(top, error).string(), top});
    } else if (fs::is_directory(status)) {
      i.system_.insert(i.system_.end(), {"--ro-bind", top, top});
    }
  }
  // Of /etc, only what finds programs and libraries (/usr/bin/c++ is a link through
  // /etc/alternatives): never the host's accounts, keys or configuration.
  i.system_.insert(i.system_.end(), {"--perms", "0755", "--dir", "/etc"});
  for (const char* file : {"/etc/ld.so.cache", "/etc/alternatives"})
    i.system_.insert(i.system_.end(), {"--ro-bind-try", file, file});
  i.namespaces_ = true;
  ProcessPool pool(1);
  Command c;
  c.argv = i.wrap({"/usr/bin/true"}, plain_environment(), View{});
  c.status_channel = true;
  c.env = plain_environment();
  c.directory = "/";
  c.limits.wall_seconds = c.limits.cpu_seconds = 30;
  Outcome outcome;
  pool.add(std::move(c), [&](Outcome o) { outcome = std::move(o); });
  pool.run();
  if (!outcome.exited || outcome.exit_code != 0) {
    i.namespaces_ = false;
    i.why_not_ = outcome.start_error.empty() ? last_line(outcome.output) : outcome.start_error;
    if (i.why_not_.empty()) i.why_not_ = "bwrap failed with no message";
  }
  return i;
}

std::vector<std::string> Isolation::wrap(const std::vector<std::string>& argv,
                                         const std::vector<std::string>& env,
                                         const View& view) const {
  if (!namespaces_) {  // the same command, with the host's paths
    std::vector<std::string> plain = argv;
    for (std::string& arg : plain)
      for (const Binding& b : view.bindings)
        if (!b.inside.empty() && arg == b.inside.string()) arg = b.path.string();
    return plain;
  }
  std::vector<std::string> w = {bwrap_};
  // As root, bubblewrap mounts with root's rights and setpriv then drops them for nobody; as
  // anyone else it makes a user namespace, which it then forbids the command to make again.
  if (::geteuid() == 0)
    w.insert(w.end(), {"--unshare-ipc", "--unshare-pid", "--unshare-net", "--unshare-uts",
                       "--unshare-cgroup-try"});
  else
    w.insert(w.end(), {"--unshare-user", "--unshare-ipc", "--unshare-pid", "--unshare-net",
                       "--unshare-uts", "--unshare-cgroup-try", "--disable-userns"});
  // Its own report on fd 5 (Command::status_channel), which it closes before the command starts.
  w.insert(w.end(), {"--die-with-parent", "--json-status-fd", "5", "--clearenv"});
  for (const std::string& e : env) {
    const auto eq = e.find('=');
    w.insert(w.end(),
             {"--setenv", e.substr(0, eq), eq == std::string::npos ? "" : e.substr(eq + 1)});
  }
  w.insert(w.end(), system_.begin(), system_.end());
  w.insert(w.end(), {"--proc", "/proc", "--dev", "/dev", "--perms", "1777", "--size",
                     std::to_string(view.scratch_mb << 20), "--tmpfs", "/tmp"});
  // A folder of the kit's under /usr (a kit installed there) is hidden behind an empty one.
  for (const fs::path& h : hide_)
    if (is_within(h, "/usr")) w.insert(w.end(), {"--tmpfs", h.string()});
  // The folders on the way to each binding, made here, readable by everyone (bubblewrap makes
  // them for root only, which the command, as nobody, could not pass).
  std::vector<fs::path> made = {"/", "/tmp", "/usr", "/etc", "/proc", "/dev"};
  for (const Binding& b : view.bindings) {
    const fs::path inside = b.inside.empty() ? b.path : b.inside;
    std::vector<fs::path> way;
    for (fs::path p = inside.parent_path(); !p.empty() && p != p.root_path(); p = p.parent_path())
      way.push_back(p);
    for (auto it = way.rbegin(); it != way.rend(); ++it)
      if (std::find(made.begin(), made.end(), *it) == made.end()) {
        made.push_back(*it);
        w.insert(w.end(), {"--perms", "0755", "--dir", it->string()});
      }
    w.insert(w.end(), {b.writable ? "--bind" : "--ro-bind", b.path.string(), inside.string()});
  }
  w.insert(w.end(), {"--chdir", view.directory.empty() ? "/tmp" : view.directory.string(), "--"});
  if (::geteuid() == 0)
    w.insert(w.end(), {setpriv_, "--reuid=65534", "--regid=65534", "--clear-groups",
                       "--inh-caps=-all", "--bounding-set=-all", "--no-new-privs", "--"});
  w.insert(w.end(), argv.begin(), argv.end());
  return w;
}

void Isolation::confine(Command& c, const View& view) const {
  c.argv = wrap(c.argv, c.env, view);
  c.status_channel = namespaces_;
  if (namespaces_) return;
  c.run_as = run_as_;
  if (users_apart_) {
    c.run_as = users_from;
    c.group = nobody;
    c.user_per_slot = true;
  }
  if (!view.test) c.filter = filter_;
  if (!view.directory.empty())
    for (const Binding& b : view.bindings)
      if (view.directory == (b.inside.empty() ? b.path : b.inside)) c.directory = b.path.string();
}

bool Isolation::never_made(const Outcome& o) const {
  if (!namespaces_ || o.stopped != Stop::none) return false;  // no sandbox, or the grader ended it
  const bool failed = !o.exited || o.exit_code != 0;
  return failed && o.status.find("\"exit-code\"") == std::string::npos;
}

std::string Isolation::why_never_made(const Outcome& o) {
  // The command never ran, so everything printed is bubblewrap's.
  std::string why;
  std::istringstream lines(o.output);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("bwrap: ", 0) == 0) why = line.substr(7);
  if (why.empty())
    why = o.exited ? "bubblewrap ended with status " + std::to_string(o.exit_code)
                   : "bubblewrap ended by signal " + std::to_string(o.signal);
  return why;
}

std::string Isolation::describe() const {
  std::ostringstream text;
  const std::string user = run_as_ == nobody ? "the user nobody" : "the grading user";
  if (namespaces_) {
    text << "sandbox: every compiler, linker and test process of a submission runs in namespaces "
         << "of its own (bubblewrap: mount, PID, network, IPC, UTS), as " << user
         << ", seeing only the system's /usr, the kit's public headers and its own copy, "
         << "read-only, and a size-limited scratch";
  } else {
    const std::string users = users_apart_
                                  ? "users " + std::to_string(users_from) + "-" +
                                        std::to_string(users_from + ProcessPool::users_apart - 1) +
                                        " (one per command running at once)"
                                  : user;
    text << "no sandbox: namespaces cannot be had here (" << why_not_ << "), so submission code "
         << "is compiled and tested as " << users << ", in a process group of its own, the "
         << "builds under a system-call filter (no signal beyond their own group, no tracing, "
         << "no network), the tests under the test process's filter and Landlock (where the "
         << "kernel has it), and can read whatever " << user << " can read";
    if (!why_not_apart_.empty()) text << " (not a user per command: " << why_not_apart_ << ")";
  }
  return text.str();
}

void Isolation::give_to_sandbox(const fs::path& folder) const {
  if (run_as_ == nobody) {
    [[maybe_unused]] const int ignored = ::chown(folder.c_str(), nobody, nobody);
  }
  // Users apart write there as the group nogroup (a task's link replaces what its compilations
  // wrote as other users); no one else may.
  if (users_apart_ && !namespaces_) {
    std::error_code error;
    fs::permissions(folder, fs::perms::owner_all | fs::perms::group_all, error);
  }
}

}  // namespace springlab::grader
