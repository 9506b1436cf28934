// Linked into the sanitized programs only: the sanitizers' options, which the run-time asks for
// at start, instead of ASAN_OPTIONS and UBSAN_OPTIONS in the environment, so that a test process
// sees the same environment in the plain and the sanitized run. No leak checks (they need ptrace,
// which the test process may not use); a failed assertion reports its stack; a failed allocation
// throws, as in the plain run.
extern "C" const char* __asan_default_options() {
  return "detect_leaks=0:handle_abort=1:allocator_may_return_null=1:exitcode=1";
}

extern "C" const char* __ubsan_default_options() {
  return "print_stacktrace=1:halt_on_error=1";
}
