#pragma once

namespace fovrt {

// In an AddressSanitizer build, marks every shared library loaded now as never unloaded, so
// LeakSanitizer's scan at exit still sees the memory of the Vulkan driver and layers that the
// loader dlcloses at vkDestroyInstance: a block whose only reference lives there would otherwise be
// reported as leaked from "<unknown module>", with no name a suppression could match.
// Does nothing in other builds.
void KeepLoadedLibrariesForLeakCheck();

}  // namespace fovrt
