// The layout of a .vdb file checked before OpenVDB reads it: OpenVDB allocates and reads
// whatever sizes a file claims (a 100-byte truncated file asked for 4 GB; a corrupt chunk size
// for 8e18 bytes, or a heap overflow), so every length, count and offset in the header, the
// metadata, the grid descriptors and (detail/vdb_tree_walk.h) the trees must fit the file and
// agree with each other. Files older than format version 218 are refused; trees of other node
// sizes or value types than voxgi's are checked down to their root node only.
#pragma once

#include <string>

namespace voxgi {

// InputError "<path>: ..." naming the first field that does not fit.
void checkVdbStructure(const std::string& path);

}  // namespace voxgi
