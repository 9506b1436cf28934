// Keeps the OpenGL driver that Mesa loaded for the window in memory until the program ends.
#pragma once

namespace springlab::view {

/// Mesa unloads its driver (swrast_dri.so) with the last GL context. LeakSanitizer, which runs
/// after that, then cannot name the driver's own leftover allocations, and the suppressions in
/// tests/viewer/lsan.supp cannot match them. Marking the loaded driver resident costs nothing.
/// Only with glibc (dl_iterate_phdr), where those suppressions apply; elsewhere it does nothing.
void keep_gl_driver_loaded();

}  // namespace springlab::view
