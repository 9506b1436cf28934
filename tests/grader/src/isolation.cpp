#include "isolation.hpp"

#include "policy.hpp"
#include "process.hpp"

#include <unistd.h>

#include <algorithm>
#include <sstream>

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

}  // namespace

Isolation Isolation::without_namespaces(const std::string& why) {
  Isolation i;
  i.why_not_ = why;
  i.run_as_ = ::geteuid() == 0 ? nobody : uid_t(-1);
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
    text << "no sandbox: namespaces cannot be had here (" << why_not_ << "), so submission code "
         << "is compiled and tested as " << user << ", under the test process's system-call "
         << "filter and Landlock (where the kernel has it), and can read whatever " << user
         << " can read";
  }
  return text.str();
}

void Isolation::give_to_sandbox(const fs::path& folder) const {
  if (run_as_ == nobody) {
    [[maybe_unused]] const int ignored = ::chown(folder.c_str(), nobody, nobody);
  }
}

}  // namespace springlab::grader
