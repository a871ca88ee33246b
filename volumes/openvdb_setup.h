// OpenVDB needs its grid types registered once per process before any file I/O.
#pragma once

namespace voxgi {

// Thread-safe and idempotent.
void initializeOpenVdb();

}  // namespace voxgi
