// What springlab-view asks of the operating system, one function each: POSIX systems (Linux, the
// BSDs, macOS) and Windows answer in platform.cpp, so that main.cpp needs no system header.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace springlab::view::platform {

/// Whether `folder` is a folder this process may create files in.
bool can_write_in(const std::filesystem::path& folder);
/// Opens `path` for writing as an image writer would, without truncating a file there already
/// and without waiting on a FIFO, and removes again a file made for the purpose. Returns why it
/// cannot be written, or "" when it can.
std::string probe_writable(const std::string& path);
/// The process's limit on its address space (ulimit -v), bytes; none when unlimited, or where
/// the system has no such limit (Windows).
std::optional<double> address_space_limit();
/// Under a limit on address space or data (ulimit -v, ulimit -d), one malloc arena for every
/// thread (main.cpp says why); nothing where malloc has no per-thread arenas to limit.
void one_arena_under_memory_limits();
/// Sets an environment variable unless it is set already.
void set_environment_default(const char* name, const char* value);
bool standard_error_is_terminal();
/// A write to a closed pipe then fails with an error instead of killing the process (POSIX's
/// SIGPIPE); Windows has no such signal.
void ignore_broken_pipes();

}  // namespace springlab::view::platform
