#include "verdict.hpp"

#include "sanitizer.hpp"

#include <seccomp.h>
#include <signal.h>
#include <sys/random.h>
#include <algorithm>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>

namespace springlab::grader {
namespace {

// The records of a run: kind -> payload, from "<secret> <kind> <size>\n<payload>". Only the
// harness knows the secret, so whatever else reached fd 3 is skipped over.
std::map<std::string, std::string> records_of(const std::string& text, const std::string& secret) {
  std::map<std::string, std::string> records;
  for (std::size_t at = text.find(secret); at != std::string::npos;
       at = text.find(secret, at + 1)) {
    const auto end_of_line = text.find('\n', at);
    if (end_of_line == std::string::npos) break;
    std::istringstream header(text.substr(at + secret.size(), end_of_line - at - secret.size()));
    std::string kind;
    std::size_t size = 0;
    if (!(header >> kind >> size) || size > text.size() - end_of_line - 1) continue;
    records.emplace(kind, text.substr(end_of_line + 1, size));
    at = end_of_line + size;
  }
  return records;
}

std::string seconds(double s) {
  std::ostringstream out;
  out.precision(s < 10 ? 2 : 3);
  out << s << " s";
  return out.str();
}

// The "key value" lines of the harness's record of how the worker ended.
std::map<std::string, std::string> fields_of(const std::string& record) {
  std::map<std::string, std::string> fields;
  std::istringstream lines(record);
  std::string line;
  while (std::getline(lines, line)) {
    const auto space = line.find(' ');
    fields[line.substr(0, space)] = space == std::string::npos ? "" : line.substr(space + 1);
  }
  return fields;
}

const std::string forbidden_text =
    "). While tests run, code may not start programs or threads, change files or signal other "
    "processes";

// Why the worker (the process running the submission's code) did not finish the test, in words;
// "" when it did, and the test's own first failure is the reason.
std::string worker_ending(const std::string& record, const std::string& output,
                          const Limits& limits, const LimitsText& text);

// The same, saying which of the task's functions was running when the worker ended, where a
// task function was (the harness knows which call it awaited an answer to).
std::string worker_ending_where(const std::string& record, const std::string& output,
                                const Limits& limits, const LimitsText& text) {
  const auto w = fields_of(record);
  std::string words = worker_ending(record, output, limits, text);
  if (words.empty() || w.count("in") == 0 || words.rfind("timed out in ", 0) == 0) return words;
  const std::string inputs = w.count("inputs") > 0 ? w.at("inputs") : "";
  if (words.find(w.at("in")) != std::string::npos) {  // named already, by the sanitizer's stack
    if (!inputs.empty())
      words.insert(std::min(words.find('\n'), words.size()), "; it was called with " + inputs);
    return words;
  }
  // "hold_pinned (called with pinned: 9 entries, acceleration: 2x9)": the sizes it was given.
  const std::string function = w.at("in") + (inputs.empty() ? "" : " (called with " + inputs + ")");
  if (words.rfind("a check failed", 0) == 0 || words.rfind("crashed", 0) == 0 ||
      words.rfind("memory error", 0) == 0 || words.rfind("exited before", 0) == 0 ||
      words.rfind("undefined behaviour", 0) == 0) {
    if (words.rfind("a check failed: ", 0) == 0) {
      words.insert(14, " while your " + function + " was running");
    } else {
      const auto line_end = std::min(words.find('\n'), words.size());
      words.insert(line_end, " (while your " + function + " was running)");
    }
  }
  return words;
}

std::string worker_ending(const std::string& record, const std::string& output,
                          const Limits& limits, const LimitsText& text) {
  const auto w = fields_of(record);
  const std::string stopped = w.count("stopped") > 0 ? w.at("stopped") : "";
  if (stopped.rfind("forbidden ", 0) == 0)
    return "stopped: your code asked the system for something tests never need (" +
           system_call_name(std::atol(stopped.c_str() + 10)) + forbidden_text;
  if (stopped.rfind("refused ", 0) == 0) return "not run: " + stopped.substr(8);
  if (stopped.rfind("timed out in ", 0) == 0)
    return stopped + ", and the test may take " + text.time +
           " in all: your function did not return (an endless loop in it?)";
  if (w.count("memory") > 0) return "used more than " + w.at("memory") + " MB of memory: stopped";
  const bool finished = w.count("complete") > 0 && w.at("complete") == "1" && w.count("exit") > 0 &&
                        w.at("exit") == "0";
  if (finished && stopped.empty()) return "";
  const std::string report = explain_sanitizer_report(output);
  if (!report.empty()) return report;
  if (w.count("signal") > 0) {
    const int signal = std::atoi(w.at("signal").c_str());
    if (signal == SIGXCPU || (signal == SIGKILL && stopped.empty()))
      return "used more than " + seconds(std::ceil(limits.cpu_seconds)) +
             " of processor time (the limit is " + text.time + "): stopped";
    if (signal == SIGSYS)
      return "stopped: your code asked the system for something tests never need" +
             forbidden_text.substr(1);
    if (signal != SIGKILL) return "crashed: " + signal_text(signal);
  }
  if (w.count("loaded") > 0 && w.at("loaded") == "0")
    return "ended while your code was being loaded, before the test began (" +
           (w.count("exit") > 0 ? "exit status " + w.at("exit") : std::string("killed")) +
           "): does the initialiser of a global variable call exit()?";
  if (!finished && w.count("exit") > 0) return early_exit_text(w.at("exit"));
  // The worker finished, but its answers did not fit the test.
  return "your code's answers could not be checked: " + stopped;
}

}  // namespace

std::string new_secret() {
  unsigned char bytes[16];
  std::size_t got = 0;
  while (got < sizeof bytes) {
    const ssize_t n = getrandom(bytes + got, sizeof bytes - got, 0);
    if (n > 0) got += std::size_t(n);
  }
  static const char digits[] = "0123456789abcdef";
  std::string secret;
  for (const unsigned char b : bytes)
    secret += {digits[b >> 4], digits[b & 15]};
  return secret;
}

std::string system_call_name(long number) {
  char* name = seccomp_syscall_resolve_num_arch(SCMP_ARCH_NATIVE, int(number));
  std::string result = name ? name : "number " + std::to_string(number);
  std::free(name);
  return result;
}

RunVerdict judge(const Outcome& o, const std::string& secret, const Limits& limits,
                 const LimitsText& text) {
  if (!o.start_error.empty())
    return {false, "the grader could not start the test: " + o.start_error};
  switch (o.stopped) {
    case Stop::wall_time:
      return {false, timed_out_text(seconds(o.wall_seconds), text.time)};
    case Stop::cpu_time:
      return {false, "used more than " + seconds(std::ceil(limits.cpu_seconds)) +
                         " of processor time (the limit is " + text.time + "): stopped"};
    case Stop::output:
      return {false, output_limit_text(long(limits.output_limit >> 20))};
    case Stop::memory:
      return {false,
              "used more than " + std::to_string(limits.resident_mb) + " MB of memory: stopped"};
    case Stop::none:
      break;
  }
  const auto records = records_of(o.records, secret);
  if (const auto it = records.find("error"); it != records.end())
    return {false, "the test could not run: " + it->second};
  const auto verdict = records.find("verdict");
  const auto worker_record = records.find("worker");
  if (verdict == records.end() || worker_record == records.end() || !o.exited || o.exit_code != 0)
    return {false, "the test program ended without a verdict (" +
                       (o.exited ? "exit status " + std::to_string(o.exit_code)
                                 : "signal " + std::to_string(o.signal)) +
                       "): the kit's fault, not yours; please report it"};
  const std::string& payload = verdict->second;
  const bool passed = payload.rfind("pass ", 0) == 0;
  if (passed) return {true, ""};
  const auto newline = payload.find('\n');
  std::string message = newline == std::string::npos ? "" : payload.substr(newline + 1);
  if (message.empty()) message = "no check ran";
  const std::string why = worker_ending_where(worker_record->second, o.output, limits, text);
  if (!why.empty()) return {false, why};
  if (message.find("std::bad_alloc") != std::string::npos && limits.address_space_mb > 0)
    message += "\n(out of memory: the limit is " + std::to_string(limits.address_space_mb) + " MB)";
  return {false, message};
}

}  // namespace springlab::grader
