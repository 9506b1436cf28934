#include "process.hpp"

#include <fcntl.h>
#include <grp.h>
#include <linux/close_range.h>
#include <linux/seccomp.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <deque>
#include <fstream>
#include <list>
#include <system_error>
#include <utility>

namespace springlab::grader {
namespace {

using Clock = std::chrono::steady_clock;

// What the sandbox's status channel may bring: a few JSON lines (bubblewrap's child pid, then its
// exit code).
constexpr std::size_t status_limit = 64 * 1024;

volatile std::sig_atomic_t interrupted_by = 0;  // the signal that asked the grader to stop

// A file descriptor that closes itself.
class Fd {
 public:
  Fd() = default;
  explicit Fd(int fd) : fd_(fd) {}
  Fd(Fd&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  Fd& operator=(Fd&& other) noexcept {
    reset(std::exchange(other.fd_, -1));
    return *this;
  }
  ~Fd() { reset(); }
  int get() const { return fd_; }
  void reset(int fd = -1) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = fd;
  }

 private:
  int fd_ = -1;
};

struct Pipe {
  Fd read, write;
};

Pipe make_pipe() {
  int ends[2];
  if (::pipe2(ends, O_CLOEXEC) != 0)
    throw std::system_error(errno, std::generic_category(), "pipe");
  return {Fd(ends[0]), Fd(ends[1])};
}

void set_limit(int resource, rlim_t soft, rlim_t hard) {
  const rlimit limit{soft, hard};
  ::setrlimit(resource, &limit);
}

// In the child: the filter's placeholders for its own group given its pid (which is its group's),
// then loaded. Its own copy of the program, so the parent's stays as it was.
bool load_filter(std::vector<sock_filter>& program) {
  const auto self = std::uint32_t(::getpid());
  const std::uint32_t group = SystemCallFilter::own_group;
  for (sock_filter& step : program) {
    if (BPF_CLASS(step.code) != BPF_JMP || BPF_SRC(step.code) != BPF_K) continue;
    if (step.k == group) step.k = self;
  }
  const sock_fprog loaded = {static_cast<unsigned short>(program.size()), program.data()};
  return ::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) == 0 &&
         ::syscall(SYS_seccomp, SECCOMP_SET_MODE_FILTER, 0, &loaded) == 0;
}

// In the child, between fork and exec: only async-signal-safe calls (a filter's program was
// copied before the fork, and is only written here).
[[noreturn]] void become(const Command& c, int slot, std::vector<sock_filter>* filter, pid_t parent,
                         int out, int records, int secret, int status, int exec_error,
                         char* const* argv, char* const* env) {
  ::setsid();  // its own process group, to be killed whole, and no controlling terminal
  // Move the ends out of the way of 0-5 first: a pipe may have been given one of those numbers.
  const int moved_out = ::fcntl(out, F_DUPFD_CLOEXEC, 10);
  const int moved_records = records >= 0 ? ::fcntl(records, F_DUPFD_CLOEXEC, 10) : -1;
  const int moved_secret = secret >= 0 ? ::fcntl(secret, F_DUPFD_CLOEXEC, 10) : -1;
  const int moved_status = status >= 0 ? ::fcntl(status, F_DUPFD_CLOEXEC, 10) : -1;
  const int null = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  ::dup2(null, 0);
  ::dup2(moved_out, 1);
  ::dup2(moved_out, 2);
  // Nothing else the grader inherited (a terminal's, a CI runner's descriptors) reaches the child:
  // 3 to 5 unless given here, and everything above.
  const int given[] = {moved_records, moved_secret, moved_status};
  for (int fd = 3; fd <= 5; ++fd)
    if (given[fd - 3] >= 0)
      ::dup2(given[fd - 3], fd);
    else
      ::fcntl(fd, F_SETFD, FD_CLOEXEC);
  ::close_range(6, ~0U, CLOSE_RANGE_CLOEXEC);
  struct sigaction standard = {};
  standard.sa_handler = SIG_DFL;
  ::sigaction(SIGPIPE, &standard, nullptr);
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);

  const Limits& l = c.limits;
  const auto cpu = rlim_t(std::ceil(l.cpu_seconds));
  set_limit(RLIMIT_CPU, cpu, cpu + 1);  // SIGXCPU at the limit, SIGKILL a second later
  if (l.address_space_mb > 0)
    set_limit(RLIMIT_AS, rlim_t(l.address_space_mb) << 20, rlim_t(l.address_space_mb) << 20);
  set_limit(RLIMIT_FSIZE, rlim_t(l.file_size_mb) << 20, rlim_t(l.file_size_mb) << 20);
  set_limit(RLIMIT_CORE, 0, 0);
  set_limit(RLIMIT_NOFILE, 256, 256);
  if (c.run_as != uid_t(-1)) {  // the grader is root: the child is not
    const uid_t user = c.user_per_slot ? c.run_as + uid_t(slot) : c.run_as;
    const gid_t group = c.group != gid_t(-1) ? c.group : gid_t(c.run_as);
    if (::setgroups(0, nullptr) != 0 || ::setresgid(group, group, group) != 0 ||
        ::setresuid(user, user, user) != 0 || ::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0))
      ::_exit(127);
    // Users apart share their files through their group: a task's link reads and replaces what
    // its compilations, run as other users, wrote.
    if (c.user_per_slot) ::umask(002);
  }
  // Killed with the grader, however it ends (set after the change of user, which clears it).
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(127);
  if ((filter == nullptr || load_filter(*filter)) && ::chdir(c.directory.c_str()) == 0)
    ::execve(argv[0], argv, env);
  const int error = errno;
  [[maybe_unused]] const ssize_t ignored = ::write(exec_error, &error, sizeof error);
  ::_exit(127);
}

struct Job {
  Command command;
  std::function<void(Outcome)> done;
};

struct Running {
  Job job;
  int slot = 0;  // which of the pool's `parallel` places it has
  pid_t pid = -1;
  Fd pidfd, out, records, status;
  Clock::time_point start, deadline, next_memory_check;
  Outcome outcome;
};

std::vector<char*> pointers(std::vector<std::string>& strings) {
  std::vector<char*> result;
  for (std::string& s : strings)
    result.push_back(s.data());
  result.push_back(nullptr);
  return result;
}

long resident_kb(pid_t pid) {
  std::ifstream statm("/proc/" + std::to_string(pid) + "/statm");
  long size = 0, resident = 0;
  statm >> size >> resident;
  return resident * (::sysconf(_SC_PAGESIZE) / 1024);
}

// The child's resident memory and all its descendants' (a sandbox, a test's harness and its
// worker), a few levels deep.
long resident_kb_with_children(pid_t pid, int depth = 0) {
  long total = resident_kb(pid);
  std::ifstream children("/proc/" + std::to_string(pid) + "/task/" + std::to_string(pid) +
                         "/children");
  for (pid_t child = 0; depth < 6 && children >> child;)
    total += resident_kb_with_children(child, depth + 1);
  return total;
}

}  // namespace

struct ProcessPool::Impl {
  int parallel;
  std::deque<Job> queued;
  std::list<Running> running;

  int free_slot() const;
  void start(Job job);
  void read_from(Running& r, bool drain);
  void stop(Running& r, Stop why);
  void finish(std::list<Running>::iterator it, const rusage& usage, int status);
  void step();
};

int ProcessPool::Impl::free_slot() const {
  for (int slot = 0;; ++slot)
    if (std::none_of(running.begin(), running.end(),
                     [slot](const Running& r) { return r.slot == slot; }))
      return slot;
}

void ProcessPool::Impl::start(Job job) {
  Running r;
  r.job = std::move(job);
  r.slot = free_slot();
  const Command& c = r.job.command;
  Pipe out = make_pipe(), exec_error = make_pipe(), records, secret, status;
  if (!c.secret.empty()) {
    records = make_pipe();
    secret = make_pipe();
  }
  if (c.status_channel) status = make_pipe();
  std::vector<std::string> argv = c.argv, env = c.env;
  std::vector<char*> argv_p = pointers(argv), env_p = pointers(env);
  std::vector<sock_filter> filter;
  if (c.filter) filter = c.filter->program;

  r.start = Clock::now();
  const pid_t self = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    r.outcome.start_error = std::string("fork: ") + std::strerror(errno);
    r.job.done(std::move(r.outcome));
    return;
  }
  if (pid == 0)
    become(c, r.slot % users_apart, c.filter ? &filter : nullptr, self, out.write.get(),
           records.write.get(), secret.read.get(), status.write.get(), exec_error.write.get(),
           argv_p.data(), env_p.data());
  r.pid = pid;
  exec_error.write.reset(), out.write.reset(), records.write.reset(), secret.read.reset();
  status.write.reset();
  int error = 0;
  if (::read(exec_error.read.get(), &error, sizeof error) == sizeof error) {
    ::waitpid(pid, nullptr, 0);
    r.outcome.start_error = "cannot run " + c.argv.front() + ": " + std::strerror(error);
    r.job.done(std::move(r.outcome));
    return;
  }
  if (!c.secret.empty()) {
    // 32 bytes fit in any pipe's buffer: this never blocks, and a child already gone gets EPIPE.
    [[maybe_unused]] const ssize_t sent =
        ::write(secret.write.get(), c.secret.data(), c.secret.size());
    secret.write.reset();
  }
  r.pidfd = Fd(int(::syscall(SYS_pidfd_open, pid, 0)));  // readable once the child has ended
  r.out = std::move(out.read);
  r.records = std::move(records.read);
  r.status = std::move(status.read);
  for (const Fd* fd : {&r.out, &r.records, &r.status})
    if (fd->get() >= 0) ::fcntl(fd->get(), F_SETFL, O_NONBLOCK);
  r.deadline = r.start + std::chrono::duration_cast<Clock::duration>(
                             std::chrono::duration<double>(c.limits.wall_seconds));
  r.next_memory_check = r.start;
  running.push_back(std::move(r));
}

void ProcessPool::Impl::stop(Running& r, Stop why) {
  if (r.outcome.stopped == Stop::none) r.outcome.stopped = why;
  ::kill(-r.pid, SIGKILL);
}

void ProcessPool::Impl::read_from(Running& r, bool drain) {
  char buffer[65536];
  const Limits& limits = r.job.command.limits;
  for (Fd* fd : {&r.out, &r.records, &r.status}) {
    while (fd->get() >= 0) {
      const ssize_t n = ::read(fd->get(), buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) break;  // EAGAIN: nothing more for now
      if (n == 0) {
        fd->reset();
        break;
      }
      const auto size = std::size_t(n);
      if (fd == &r.out) {
        const std::size_t room =
            limits.output_kept - std::min(limits.output_kept, r.outcome.output.size());
        r.outcome.output.append(buffer, std::min(room, size));
        r.outcome.output_bytes += size;
        if (r.outcome.output_bytes > limits.output_limit) stop(r, Stop::output);
      } else if (fd == &r.records && r.outcome.records.size() < limits.records_limit) {
        r.outcome.records.append(buffer,
                                 std::min(limits.records_limit - r.outcome.records.size(), size));
      } else if (fd == &r.status && r.outcome.status.size() < status_limit) {
        r.outcome.status.append(buffer, std::min(status_limit - r.outcome.status.size(), size));
      }
      if (!drain) break;  // one buffer per turn, so that a flood cannot starve the others
    }
  }
}

void ProcessPool::Impl::finish(std::list<Running>::iterator it, const rusage& usage, int status) {
  Running& r = *it;
  read_from(r, true);
  ::kill(-r.pid, SIGKILL);  // anything it left behind in its group
  Outcome& o = r.outcome;
  o.wall_seconds = std::chrono::duration<double>(Clock::now() - r.start).count();
  o.cpu_seconds = double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                  1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  o.peak_resident_kb = usage.ru_maxrss;
  o.exited = WIFEXITED(status);
  o.exit_code = o.exited ? WEXITSTATUS(status) : 0;
  o.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  if (o.stopped == Stop::none &&
      (o.signal == SIGXCPU ||
       (o.signal == SIGKILL && o.cpu_seconds >= std::ceil(r.job.command.limits.cpu_seconds))))
    o.stopped = Stop::cpu_time;
  Job job = std::move(r.job);
  Outcome outcome = std::move(r.outcome);
  running.erase(it);
  job.done(std::move(outcome));
}

void ProcessPool::Impl::step() {
  while (static_cast<int>(running.size()) < parallel && !queued.empty()) {
    Job job = std::move(queued.front());
    queued.pop_front();
    start(std::move(job));
  }
  if (running.empty()) return;

  std::vector<pollfd> fds;
  auto now = Clock::now();
  auto wake = now + std::chrono::milliseconds(200);
  for (Running& r : running) {
    for (const Fd* fd : {&r.out, &r.records, &r.status, &r.pidfd})
      if (fd->get() >= 0) fds.push_back({fd->get(), POLLIN, 0});
    if (r.pidfd.get() < 0) wake = std::min(wake, now + std::chrono::milliseconds(10));
    wake = std::min(wake, r.deadline);
    if (r.job.command.limits.resident_mb > 0) wake = std::min(wake, r.next_memory_check);
  }
  const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(wake - now).count();
  ::poll(fds.data(), fds.size(), int(std::max<long>(0, long(wait))));

  now = Clock::now();
  for (Running& r : running) {
    read_from(r, false);
    if (now >= r.deadline) stop(r, Stop::wall_time);
    const long resident_limit = r.job.command.limits.resident_mb;
    if (resident_limit > 0 && now >= r.next_memory_check) {
      r.next_memory_check = now + std::chrono::milliseconds(50);
      if (resident_kb_with_children(r.pid) > resident_limit * 1024) stop(r, Stop::memory);
    }
  }
  for (auto it = running.begin(); it != running.end();) {
    int status = 0;
    rusage usage{};
    const pid_t pid = ::wait4(it->pid, &status, WNOHANG, &usage);
    auto next = std::next(it);
    if (pid == it->pid) finish(it, usage, status);
    it = next;
  }
}

ProcessPool::ProcessPool(int parallel) : impl_(std::make_unique<Impl>()) {
  impl_->parallel = std::max(1, parallel);
  struct sigaction ignore = {};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGPIPE, &ignore, nullptr);  // a child gone before its secret arrived
}

ProcessPool::~ProcessPool() {
  for (Running& r : impl_->running) {
    ::kill(-r.pid, SIGKILL);
    ::waitpid(r.pid, nullptr, 0);
  }
}

void ProcessPool::add(Command command, std::function<void(Outcome)> done) {
  impl_->queued.push_back({std::move(command), std::move(done)});
}

void ProcessPool::run() {
  while (!impl_->queued.empty() || !impl_->running.empty()) {
    if (interrupted_by != 0) {
      impl_->queued.clear();
      for (Running& r : impl_->running) {
        ::kill(-r.pid, SIGKILL);
        ::waitpid(r.pid, nullptr, 0);
      }
      impl_->running.clear();
      throw Interrupted(interrupted_by);
    }
    impl_->step();
  }
}

void interrupt(int signal) {
  interrupted_by = signal;
}

std::vector<std::string> plain_environment() {
  // OMP_NUM_THREADS=1: the grader already runs several submissions at once, and a grading
  // process's CPU-time limit then means the same on a 2-core laptop as on a 64-core server (the
  // kit's large scenes would otherwise start a thread per core, each with its stack).
  return {"PATH=/usr/local/bin:/usr/bin:/bin", "LANG=C.UTF-8", "LC_ALL=C.UTF-8",
          "OMP_NUM_THREADS=1"};
}

}  // namespace springlab::grader
