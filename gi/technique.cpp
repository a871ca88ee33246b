#include "gi/technique.h"

#include "scenes/errors.h"

namespace voxgi {

void GiTechnique::dumpVdb(const std::string&) const {
    throw NotImplementedError("method '" + name() + "' has no .vdb dump yet");
}

DebugDrawing GiTechnique::debugView(const std::string&, const DebugViewContext&) const { return {}; }

}  // namespace voxgi
