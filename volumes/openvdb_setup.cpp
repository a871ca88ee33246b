#include "volumes/openvdb_setup.h"

#include <mutex>

#include <openvdb/io/DelayedLoadMetadata.h>
#include <openvdb/openvdb.h>

namespace voxgi {

void initializeOpenVdb() {
    static std::once_flag once;
    std::call_once(once, [] {
        openvdb::initialize();
        // voxgi reads whole grids (never delayed loading), so the per-grid "file_delayed_load"
        // metadata is not needed: unregistered, OpenVDB skips it as opaque bytes of its stated
        // size. Registered, its reader allocates whatever counts it holds (a corrupt one took
        // 8 GB), unchecked against that size.
        openvdb::Metadata::unregisterType(openvdb::io::DelayedLoadMetadata::staticTypeName());
    });
}

}  // namespace voxgi
