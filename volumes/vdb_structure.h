// The layout of a .vdb file checked before OpenVDB reads it: OpenVDB allocates whatever sizes a
// file claims (a 100-byte truncated file asked for 4 GB; a corrupt compressed-size field for
// 8e18 bytes), so every length, count and offset in the header, the file metadata and the grid
// descriptors must fit in the file. Files of other format versions than voxgi writes (220..)
// are checked for the magic number only.
#pragma once

#include <string>

namespace voxgi {

// InputError "<path>: ..." naming the first field that does not fit.
void checkVdbStructure(const std::string& path);

}  // namespace voxgi
