#include "vk/leak_check_pin.h"

#if defined(__SANITIZE_ADDRESS__)
#include <dlfcn.h>
#include <link.h>
#endif

namespace fovrt {

void KeepLoadedLibrariesForLeakCheck() {
#if defined(__SANITIZE_ADDRESS__)
    dl_iterate_phdr(
        [](dl_phdr_info* info, size_t, void*) {
            // RTLD_NOLOAD: only libraries already mapped; RTLD_NODELETE: never unmapped. The handle
            // adds a reference that is kept on purpose, for the same reason.
            if (info->dlpi_name && info->dlpi_name[0] != '\0')
                dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
            return 0;
        },
        nullptr);
#endif
}

}  // namespace fovrt
