// Children under limits: what a child prints, how it ends, and the limits the grader enforces
// itself, shown with the shell. Nothing here depends on how fast the machine is: the limits are
// far from what the commands need, or the commands never end by themselves.
#include "process.hpp"
#include "lab_catch.hpp"

#include <csignal>

using namespace springlab::grader;

namespace {

Outcome run_shell(const std::string& script, Limits limits = {}, const std::string& secret = "") {
  ProcessPool pool(2);
  Command c;
  c.argv = {"/bin/sh", "-c", script};
  c.env = plain_environment();
  c.directory = "/";
  c.limits = limits;
  c.secret = secret;
  Outcome result;
  pool.add(std::move(c), [&](Outcome o) { result = std::move(o); });
  pool.run();
  return result;
}

}  // namespace

TEST_CASE("A child's output and exit status reach the grader", "[process]") {
  const Outcome o = run_shell("echo out; echo err >&2; exit 3");
  CHECK(o.exited);
  CHECK(o.exit_code == 3);
  CHECK(o.output == "out\nerr\n");
  CHECK(o.output_bytes == 8);
  CHECK(o.stopped == Stop::none);
}

TEST_CASE("A child's environment is the grader's fixed one, not the grader's own", "[process]") {
  setenv("SPRINGLAB_SECRET_OF_THE_GRADER", "x", 1);
  CHECK(run_shell("env").output.find("SPRINGLAB_SECRET_OF_THE_GRADER") == std::string::npos);
}

TEST_CASE("The secret arrives on fd 4 and records come back on fd 3", "[process]") {
  const Outcome o = run_shell("read s <&4; echo \"$s record\" >&3", {}, "0123456789abcdef");
  CHECK(o.records == "0123456789abcdef record\n");
  CHECK(o.output.empty());
}

TEST_CASE("A child that never ends is stopped at its wall-clock limit, with everything it started",
          "[process]") {
  Limits limits;
  limits.wall_seconds = 0.5;
  const Outcome o = run_shell("sleep 1000 & sleep 1000", limits);
  CHECK(o.stopped == Stop::wall_time);
  CHECK_FALSE(o.exited);
  CHECK(o.signal == SIGKILL);
}

TEST_CASE("A child that computes forever is stopped at its processor-time limit", "[process]") {
  Limits limits;
  limits.cpu_seconds = 1;
  limits.wall_seconds = 600;
  const Outcome o = run_shell("while :; do :; done", limits);
  CHECK(o.stopped == Stop::cpu_time);
  CHECK(o.cpu_seconds > 0.5);
}

TEST_CASE("A flood of output is kept only up to its limit, counted, and then stopped",
          "[process]") {
  Limits limits;
  limits.output_kept = 1000;
  limits.output_limit = 1u << 20;
  const Outcome o = run_shell("yes springlab", limits);
  CHECK(o.stopped == Stop::output);
  CHECK(o.output.size() == 1000);
  CHECK(o.output_bytes > limits.output_limit);
}

TEST_CASE("Memory: an address-space limit fails large allocations", "[process]") {
  Limits limits;
  limits.address_space_mb = 64;
  // perl needs about 10 MB; a 200 MB string does not fit in 64.
  const Outcome o =
      run_shell("exec perl -e '$x = \"a\" x (200 * 1024 * 1024); print length $x'", limits);
  CHECK_FALSE((o.exited && o.exit_code == 0));
  CHECK(o.output.find("209715200") == std::string::npos);
}

TEST_CASE("Memory: a child whose resident memory passes the watched limit is stopped",
          "[process]") {
  Limits limits;
  limits.address_space_mb = 0;
  limits.resident_mb = 50;
  limits.wall_seconds = 600;
  // Grows by 10 MB at a time and never ends by itself.
  const Outcome o = run_shell(
      "exec perl -e '$x = \"\"; while (1) { $x .= \"a\" x (10 * 1024 * 1024); select(undef, undef, "
      "undef, 0.01) }'",
      limits);
  CHECK(o.stopped == Stop::memory);
}

TEST_CASE("A child cannot write files larger than its limit", "[process]") {
  Limits limits;
  limits.file_size_mb = 0;
  const std::string file = "/tmp/springlab-process-test-file";
  std::remove(file.c_str());
  const Outcome o = run_shell("head -c 100000 /dev/zero > " + file, limits);
  CHECK_FALSE((o.exited && o.exit_code == 0));
  std::remove(file.c_str());
}

TEST_CASE("A program that does not exist is reported, not run", "[process]") {
  ProcessPool pool(1);
  Command c;
  c.argv = {"/nonexistent/program"};
  c.directory = "/";
  Outcome result;
  pool.add(std::move(c), [&](Outcome o) { result = std::move(o); });
  pool.run();
  CHECK_THAT(result.start_error, lab_catch::Contains("cannot run /nonexistent/program"));
}

TEST_CASE("Many children: each reported once, and callbacks may add more", "[process]") {
  ProcessPool pool(2);
  int finished = 0;
  for (int i = 0; i < 6; ++i) {
    Command c;
    c.argv = {"/bin/sh", "-c", "echo " + std::to_string(i)};
    c.env = plain_environment();
    c.directory = "/";
    pool.add(c, [&, c](Outcome o) {
      ++finished;
      CHECK(o.exit_code == 0);
      if (o.output == "0\n") pool.add(c, [&](Outcome) { ++finished; });
    });
  }
  pool.run();
  CHECK(finished == 7);
}
