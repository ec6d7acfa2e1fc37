#include "pbms/version.hpp"

// Defined for this file only (core/CMakeLists.txt): a new commit rebuilds it
// alone.
#ifndef PBMS_GIT_HASH
#define PBMS_GIT_HASH "unknown"
#endif
#ifndef PBMS_VERSION
#define PBMS_VERSION "0"
#endif

namespace pbms {

const char* version() {
  return PBMS_VERSION;
}
const char* git_hash() {
  return PBMS_GIT_HASH;
}

}  // namespace pbms
