// springlab-grade-taskN: the kit's tests of task N (SPRINGLAB_GRADED_TASK) for the grader
// (tests/grader/src/), in two roles, each in a process of its own:
//   --list                        every test of task N: "[tags]<TAB>name", one per line
//   --run NAME WORKER LIBRARY [--resident-mb MB]
//       the harness: starts WORKER --work NAME LIBRARY, runs test NAME without any submission
//       code, answering the task's functions from the worker's transcript (transcript.hpp), and
//       reports to the grader on fd 3, each record carrying the secret it sent on fd 4: "worker"
//       (how the worker ended) and "verdict" ("pass|fail PASSED FAILED" and the first failure)
//   --work NAME LIBRARY
//       the worker: restricts itself (sandbox.hpp), loads LIBRARY, runs test NAME with it and
//       writes the transcript on fd 3. Its own verdict counts for nothing.
// So the verdict comes from a process that never holds submission code.
#include "catch_runner.hpp"
#include "dispatch.hpp"
#include "record.hpp"
#include "recorder.hpp"
#include "replayer.hpp"
#include "reporter.hpp"
#include "sandbox.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <climits>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

using namespace springlab;
using namespace springlab::grading;

namespace {

constexpr int graded_task = SPRINGLAB_GRADED_TASK;
constexpr int transcript_fd = 3;  // in the worker
TranscriptWriter* writer = nullptr;

void report_forbidden(long number) {
  writer->forbidden(number);
}

[[noreturn]] void refuse(TranscriptWriter& out, const std::string& why) {
  out.event(Event::refused);
  out.out().put(why);
  out.flush(true);
  _exit(0);
}

std::string own_program() {
  char path[PATH_MAX] = {};
  const ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
  return n > 0 ? std::string(path, std::size_t(n)) : "";
}

int work(const std::string& name, const std::string& given) {
  static TranscriptWriter out(transcript_fd);
  writer = &out;
  const std::string program = own_program();
  // As /proc/self/maps names it, which foreign_code() compares with.
  char resolved[PATH_MAX] = {};
  const std::string library = realpath(given.c_str(), resolved) != nullptr ? resolved : given;
  read_only_what_tests_need(program, library);  // where the kernel has Landlock
  if (!forbid_what_tests_never_need(report_forbidden))
    refuse(out, std::string("cannot restrict the test process: ") + std::strerror(errno));
  // The table first (the library's calls of other tasks go to it), then the library.
  static Implementation submission;
  use_table(graded_task, recording(submission, out));
  // Loading runs none of the library's code (its initialisers wait: entry.cpp), so what is
  // checked here is as the loader mapped it, and once no memory may become executable the
  // initialisers cannot make any: no code runs but what the compiler made of the submission.
  void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) refuse(out, std::string("cannot load the code: ") + dlerror());
  using Bind = const Implementation* (*)(const Implementation*);
  const auto bind = reinterpret_cast<Bind>(dlsym(handle, "springlab_submission_bind"));
  const auto init = reinterpret_cast<void (*)()>(dlsym(handle, "springlab_submission_init"));
  if (bind == nullptr || init == nullptr) refuse(out, "the library has no task table");
  if (const std::string foreign = foreign_code(program, library); !foreign.empty())
    refuse(out, "your code loaded or made code that is not its own (" + foreign + ")");
  if (!forbid_new_code()) refuse(out, "cannot restrict the test process after loading");
  const Implementation* own = bind(springlab_dispatch);
  init();
  take_task(submission, *own, graded_task);
  out.event(Event::loaded);
  out.flush(true);
  run_test_named(name);
  out.event(Event::end);
  out.flush(true);
  // What the code printed with "\n" rather than std::endl is still in C stdio's buffer (where
  // std::cout writes too): the student needs it most on the test that failed. Only after the
  // end is recorded, and never through std::cout's own buffer, which the code may have
  // replaced: nothing flushing runs can change the verdict.
  std::fflush(nullptr);
  _exit(0);
}

// The worker's resident memory, kB.
long resident_kb(pid_t pid) {
  std::ifstream statm("/proc/" + std::to_string(pid) + "/statm");
  long size = 0, resident = 0;
  statm >> size >> resident;
  return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

int run(const std::string& name, const std::string& worker, const std::string& library,
        long resident_mb, double wait_limit) {
  if (!receive_secret()) return 2;
  int ends[2];
  if (pipe2(ends, O_CLOEXEC) != 0) return 2;
  const pid_t harness = getpid();
  const pid_t pid = fork();
  if (pid == 0) {
    // Killed with the harness, however it ends (where no namespace ends them together).
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != harness) _exit(127);
    dup2(ends[1], transcript_fd);  // the worker's fd 3 is the transcript, not the grader's
    const char* argv[] = {worker.c_str(), "--work", name.c_str(), library.c_str(), nullptr};
    execv(argv[0], const_cast<char* const*>(argv));
    _exit(127);
  }
  close(ends[1]);
  bool memory = false, waited = false;
  TranscriptReader in(ends[0], [&] {
    if (resident_mb > 0 && !memory && resident_kb(pid) > resident_mb * 1024) {
      memory = true;
      kill(pid, SIGKILL);
    }
    // A task function that has not answered for most of the test's time: said by name, before
    // the grader's own clock ends the whole test without knowing where it was.
    if (const auto open = awaited();
        wait_limit > 0 && !waited && open && open->seconds > wait_limit) {
      waited = true;
      std::ostringstream why;
      why.precision(2);
      why << "timed out in " << open->function << ": it gave no answer for " << open->seconds
          << " s";
      give_up(why.str());
      kill(pid, SIGKILL);
    }
  });
  use_table(graded_task, replaying(in));
  bool loaded = false, complete = false;
  const auto expect = [&](Event want) {
    try {
      const Event e = in.event();
      if (e == Event::forbidden) give_up("forbidden " + std::to_string(in.integer()));
      if (e == Event::refused) give_up("refused " + in.text(4096));
      if (e != want && !replay_failure()) give_up("the code did what the test did not ask for");
      return e == want;
    } catch (const ReplayStopped& stopped) {
      give_up(stopped.what());
      return false;
    }
  };
  loaded = expect(Event::loaded);
  if (loaded) run_test_named(name);
  if (!replay_failure()) complete = expect(Event::end);
  if (!complete) kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);

  std::string worker_record =
      "loaded " + std::to_string(loaded) + "\ncomplete " + std::to_string(complete) + "\n";
  if (WIFSIGNALED(status)) worker_record += "signal " + std::to_string(WTERMSIG(status)) + "\n";
  if (WIFEXITED(status)) worker_record += "exit " + std::to_string(WEXITSTATUS(status)) + "\n";
  if (memory) worker_record += "memory " + std::to_string(resident_mb) + "\n";
  if (replay_failure()) worker_record += "stopped " + *replay_failure() + "\n";
  if (open_when_stopped() != nullptr)
    worker_record +=
        "in " + std::string(open_when_stopped()) + "\n" +
        (inputs_when_stopped().empty() ? "" : "inputs " + inputs_when_stopped() + "\n");
  const TestOutcome& outcome = test_outcome();
  const bool passed = outcome.cases_run == 1 && outcome.passed() && complete && WIFEXITED(status) &&
                      WEXITSTATUS(status) == 0;
  std::string first_failure = outcome.first_failure;
  if (outcome.cases_run != 1 && loaded)
    first_failure = "the test spec selected " + std::to_string(outcome.cases_run) + " tests";
  std::cout.flush();
  write_record("worker", worker_record);
  write_record("verdict", std::string(passed ? "pass " : "fail ") +
                              std::to_string(outcome.assertions_passed) + " " +
                              std::to_string(outcome.assertions_failed) + "\n" + first_failure);
  _exit(0);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (argc == 2 && mode == "--list") {
    std::cout << list_tests(graded_task);
    return 0;
  }
  if (argc == 4 && mode == "--work") return work(argv[2], argv[3]);
  if (argc >= 5 && argc % 2 == 1 && mode == "--run") {
    long resident_mb = 0;
    double wait_limit = 0.0;
    for (int i = 5; i + 1 < argc; i += 2) {
      const std::string option = argv[i];
      if (option == "--resident-mb") resident_mb = std::atol(argv[i + 1]);
      if (option == "--wait-limit") wait_limit = std::atof(argv[i + 1]);
    }
    return run(argv[2], argv[3], argv[4], resident_mb, wait_limit);
  }
  std::cerr << "usage: " << argv[0]
            << " --list | --run NAME WORKER LIBRARY [--resident-mb MB] [--wait-limit S] | "
            << "--work NAME LIBRARY (springlab-grade runs it)\n";
  return 2;
}
