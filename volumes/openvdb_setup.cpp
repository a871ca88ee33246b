#include "volumes/openvdb_setup.h"

#include <mutex>

#include <openvdb/openvdb.h>

namespace voxgi {

void initializeOpenVdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

}  // namespace voxgi
