#include "gui/resident_driver.hpp"

#ifdef __GLIBC__
#include <dlfcn.h>
#include <link.h>

#include <string_view>
#endif

namespace springlab::view {

void keep_gl_driver_loaded() {
#ifdef __GLIBC__
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void*) {
        const std::string_view path = info->dlpi_name ? info->dlpi_name : "";
        // RTLD_NOLOAD finds the copy already loaded; RTLD_NODELETE keeps it (and what it uses).
        if (path.find("/dri/") != std::string_view::npos)
          dlopen(info->dlpi_name, RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
        return 0;
      },
      nullptr);
#endif
}

}  // namespace springlab::view
