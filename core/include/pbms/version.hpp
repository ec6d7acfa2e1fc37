// Which PBMS this is: the project version and the commit it was configured
// from. The manifest records them, and a checkpoint is resumed only by the
// build that wrote it.
#pragma once

namespace pbms {

[[nodiscard]] const char* version();
[[nodiscard]] const char* git_hash();  // "unknown" outside a git checkout

}  // namespace pbms
