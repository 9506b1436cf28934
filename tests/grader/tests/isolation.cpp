// The sandbox submission code runs in, seen from inside with the shell: what exists there, who
// runs, what can be written, and that nothing outlives it. Where this machine cannot make
// namespaces (some containers), the tests say why and check the fallback instead.
#include "isolation.hpp"
#include "lab_catch.hpp"

#include <unistd.h>

#include <fstream>

using namespace springlab::grader;

namespace {

struct Scratch {
  fs::path top = fs::temp_directory_path() / ("springlab-isolation-" + std::to_string(getpid()));
  Scratch() {
    fs::remove_all(top);
    fs::create_directories(top / "visible");
    fs::create_directories(top / "output");
    fs::create_directories(top / "secret");
    std::ofstream(top / "visible" / "file.txt") << "seen\n";
    std::ofstream(top / "secret" / "solution.cpp") << "never seen\n";
    fs::permissions(top, fs::perms::owner_all | fs::perms::group_exec | fs::perms::others_exec);
  }
  ~Scratch() { fs::remove_all(top); }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
};

const Isolation& isolation() {
  static const Isolation i = Isolation::probe({});
  return i;
}

Outcome run_inside(const std::string& script, const View& view, Limits limits = {}) {
  Command c;
  c.argv = {"/bin/sh", "-c", script};
  c.env = plain_environment();
  c.directory = "/";
  c.limits = limits;
  isolation().confine(c, view);
  ProcessPool pool(1);
  Outcome result;
  pool.add(std::move(c), [&](Outcome o) { result = std::move(o); });
  pool.run();
  return result;
}

// True when a process whose command line holds `marker` is still alive on this machine.
bool alive(const std::string& marker) {
  for (const auto& entry : fs::directory_iterator("/proc")) {
    std::ifstream in(entry.path() / "cmdline");
    std::string line;
    std::getline(in, line, '\n');
    if (line.find(marker) != std::string::npos && entry.path().filename() != "self") return true;
  }
  return false;
}

}  // namespace

TEST_CASE("A sandboxed command sees the system, what it is given and nothing else", "[isolation]") {
  if (!isolation().namespaces()) {
    WARN("no namespaces on this machine: " << isolation().why_not());
    CHECK_THAT(isolation().describe(),
               lab_catch::StartsWith("no sandbox: namespaces cannot be had"));
    return;
  }
  Scratch s;
  View view;
  view.bindings = {{s.top / "visible", {}, false}, {s.top / "output", {}, true}};
  view.directory = s.top / "output";
  const Outcome o = run_inside(
      "cat " + (s.top / "visible" / "file.txt").string() + "; test -e " +
          (s.top / "secret").string() + " && echo SECRET; test -e /etc/shadow && echo SHADOW; " +
          "test -e /etc/passwd && echo PASSWD; test -e /home && echo HOME; pwd; id -u; env; " +
          "test -x /usr/bin/c++ && echo COMPILER",
      view);
  INFO(o.output);
  CHECK(o.exited);
  CHECK_THAT(o.output, lab_catch::StartsWith("seen\n"));
  CHECK_THAT(o.output, !lab_catch::Contains("SECRET") && !lab_catch::Contains("SHADOW") &&
                           !lab_catch::Contains("PASSWD") && !lab_catch::Contains("HOME"));
  CHECK_THAT(o.output, lab_catch::Contains((s.top / "output").string() + "\n"));
  CHECK_THAT(o.output, lab_catch::Contains("COMPILER"));
  // An unprivileged user, and exactly the environment given.
  CHECK_THAT(o.output, !lab_catch::Contains("\n0\n"));
  for (const std::string& variable : plain_environment())
    CHECK_THAT(o.output, lab_catch::Contains(variable + "\n"));
  CHECK_THAT(o.output, !lab_catch::Contains("HOME=") && !lab_catch::Contains("USER="));
}

TEST_CASE("A sandboxed command writes only its output folder and a scratch of the given size",
          "[isolation]") {
  if (!isolation().namespaces()) {
    WARN("no namespaces on this machine: " << isolation().why_not());
    CHECK_FALSE(isolation().why_not().empty());
    return;
  }
  Scratch s;
  View view;
  view.bindings = {{s.top / "visible", {}, false}, {s.top / "output", {}, true}};
  view.scratch_mb = 1;
  isolation().give_to_sandbox(s.top / "output");
  const Outcome o = run_inside(
      "touch " + (s.top / "visible" / "x").string() + " 2>/dev/null && echo WROTE-VISIBLE; " +
          "touch " + (s.top / "output" / "x").string() + " && echo WROTE-OUTPUT; " +
          "head -c 2000000 /dev/zero > /tmp/big 2>/dev/null || echo SCRATCH-FULL; " +
          "touch /usr/x 2>/dev/null && echo WROTE-USR",
      view);
  INFO(o.output);
  CHECK(o.output == "WROTE-OUTPUT\nSCRATCH-FULL\n");
  CHECK(fs::exists(s.top / "output" / "x"));
  CHECK_FALSE(fs::exists(s.top / "visible" / "x"));
}

TEST_CASE("A sandboxed command sees no other process and no network", "[isolation]") {
  if (!isolation().namespaces()) {
    WARN("no namespaces on this machine: " << isolation().why_not());
    CHECK_FALSE(isolation().why_not().empty());
    return;
  }
  // Its processes are a handful (bubblewrap's and its own); the machine's interfaces are gone.
  const Outcome o = run_inside(
      "ls /proc | grep -c '^[0-9]'; grep -c 'springlab-grader-test[s]' /proc/[0-9]*/cmdline "
      "2>/dev/null | grep -v ':0$' | wc -l; tail -n +3 /proc/net/dev | cut -d: -f1",
      View{});
  INFO(o.output);
  std::istringstream lines(o.output);
  int processes = 0, graders = -1;
  std::string interfaces, line;
  lines >> processes >> graders;
  while (lines >> line)
    interfaces += line + " ";
  CHECK(processes > 0);
  CHECK(processes <= 5);
  CHECK(graders == 0);
  CHECK(interfaces == "lo ");
}

TEST_CASE("Nothing a sandboxed command starts outlives it", "[isolation]") {
  const std::string marker = "springlab-isolation-marker-" + std::to_string(getpid());
  Limits limits;
  limits.wall_seconds = 1;
  const Outcome o = run_inside(
      "sleep 300 " + marker + " 2>/dev/null & sleep 200 " + marker + " 2>/dev/null; sleep 100",
      View{}, limits);
  CHECK(o.stopped == Stop::wall_time);
  // The kernel reaps a killed namespace at once; allow it a moment on a busy machine.
  for (int i = 0; i < 50 && alive(marker); ++i)
    usleep(20000);
  CHECK_FALSE(alive(marker));
}

TEST_CASE("Without namespaces, commands keep the host's paths and run as nobody under root",
          "[isolation]") {
  const Isolation none = Isolation::without_namespaces("refused by this host");
  View view;
  view.bindings = {{"/host/worker", "/grade/worker", false}};
  CHECK(none.wrap({"/grade/worker", "--x"}, {}, view) ==
        std::vector<std::string>{"/host/worker", "--x"});
  Command c;
  c.argv = {"/grade/worker"};
  none.confine(c, view);
  if (geteuid() != 0)
    CHECK(c.run_as == uid_t(-1));
  else if (none.users_apart())
    CHECK((c.run_as == Isolation::users_from && c.user_per_slot && c.group == 65534));
  else
    CHECK(c.run_as == uid_t(65534));
  CHECK(c.filter);  // a build's
  CHECK_THAT(none.describe(), lab_catch::Contains("refused by this host"));
  Command test;
  view.test = true;
  none.confine(test, view);
  CHECK_FALSE(test.filter);  // the worker loads its own, and the harness must signal it
}

namespace {

// Runs the shell script `script` under `filter` (as this process's own user), in a folder of its
// own where it may write.
Outcome run_filtered(const std::string& script, std::shared_ptr<const SystemCallFilter> filter) {
  Command c;
  c.argv = {"/bin/bash", "-c", script};
  c.env = plain_environment();
  c.directory = fs::temp_directory_path().string();
  c.filter = std::move(filter);
  c.limits.file_size_mb = 32;
  ProcessPool pool(1);
  Outcome result;
  pool.add(std::move(c), [&](Outcome o) { result = std::move(o); });
  pool.run();
  return result;
}

}  // namespace

TEST_CASE("Without namespaces, a build signals nothing but its own process group", "[isolation]") {
  // Signal 0 asks the kernel whether a signal would be delivered, and delivers none: what the
  // filter refuses fails with EPERM, whoever runs the test. The grader here is this process.
  const std::string grader = std::to_string(getpid());
  const Outcome o = run_filtered(
      "kill -0 " + grader + " && echo REACHED-GRADER; kill -0 -1 && echo REACHED-ALL; " +
          "kill -0 0 && echo OWN-GROUP; (kill -0 $BASHPID) && echo REACHED-ITSELF; " +
          "setsid -w true && echo LEFT-GROUP; : </dev/tcp/127.0.0.1/9 && echo NETWORK; " +
          "printf 'int main() { return 0; }' | c++ -x c++ - -o /tmp/springlab-filtered-" + grader +
          " && echo COMPILED; rm -f /tmp/springlab-filtered-" + grader,
      Isolation::build_filter());
  INFO(o.output);
  CHECK(o.exited);
  CHECK(o.output.find("REACHED") == std::string::npos);
  CHECK(o.output.find("OWN-GROUP") != std::string::npos);
  CHECK(o.output.find("LEFT-GROUP") == std::string::npos);
  CHECK(o.output.find("NETWORK") == std::string::npos);
  CHECK(o.output.find("COMPILED") != std::string::npos);
}

TEST_CASE("Without namespaces and as root, commands running at once are users apart",
          "[isolation]") {
  const Isolation none = Isolation::without_namespaces("refused by this host");
  if (geteuid() != 0 || !none.users_apart()) {
    WARN("no users apart here: " << (geteuid() != 0 ? "not root" : none.why_not_apart()));
    return;
  }
  // The first sleeps; the second, started beside it, tries to signal it (with no filter: the
  // users alone must keep them apart).
  const std::string marker = "springlab-apart-" + std::to_string(getpid());
  const std::string scripts[] = {
      "id -u; sleep 3 # " + marker,
      "id -u; sleep 0.5; for p in $(pgrep -f '^/bin/sh -c id -u; sleep 3 # " + marker +
          "'); do echo SEEN; kill -0 $p && echo REACHED; done"};
  ProcessPool pool(2);
  std::vector<Outcome> outcomes(2);
  for (std::size_t i = 0; i < 2; ++i) {
    Command c;
    c.argv = {"/bin/sh", "-c", scripts[i]};
    c.env = plain_environment();
    c.directory = "/";
    none.confine(c, View{});
    c.filter.reset();
    pool.add(std::move(c), [&outcomes, i](Outcome o) { outcomes[i] = std::move(o); });
  }
  pool.run();
  INFO(outcomes[0].output << "---\n" << outcomes[1].output);
  CHECK(outcomes[0].output.substr(0, outcomes[0].output.find('\n')) !=
        outcomes[1].output.substr(0, outcomes[1].output.find('\n')));
  CHECK(outcomes[1].output.find("SEEN") != std::string::npos);
  CHECK(outcomes[1].output.find("REACHED") == std::string::npos);
}

TEST_CASE("Whether a sandbox was made is bubblewrap's word, never the command's output",
          "[isolation]") {
  if (!isolation().namespaces()) {
    WARN("no namespaces on this machine: " << isolation().why_not());
    return;
  }
  Scratch s;
  View view;
  view.bindings = {{s.top / "visible", {}, false}};
  // A command that ran and failed, printing what bubblewrap prints when it cannot make one: its
  // own failure, whatever it says (a compiler's messages or a test's output are the code's).
  const Outcome forged = run_inside(
      "echo 'bwrap: Creating new namespace failed: Operation not permitted' >&2; exit 1", view);
  INFO(forged.output << forged.status);
  CHECK_THAT(forged.output, lab_catch::StartsWith("bwrap: "));
  CHECK_FALSE(isolation().never_made(forged));
  // A sandbox that cannot be made (a folder to show that is gone): the grader's fault, in
  // bubblewrap's words.
  view.bindings.push_back({s.top / "gone", {}, false});
  const Outcome gone = run_inside("exit 0", view);
  INFO(gone.output << gone.status);
  CHECK(isolation().never_made(gone));
  CHECK_THAT(Isolation::why_never_made(gone), lab_catch::Contains("gone"));
  // And a command that ran and succeeded is never the grader's fault.
  CHECK_FALSE(isolation().never_made(run_inside("true", {})));
}
