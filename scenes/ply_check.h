// A PLY file checked before assimp reads it. assimp 5.2 loops for seconds on some malformed
// headers and reserves whatever counts a file claims (a header's 2e9 vertices: 24 GB; an ASCII
// face's list count of 3e18), so the whole file is walked first: every header line is a known
// keyword with the right number of well-formed words, every element item fits in the file, and
// every list count is a plain integer that the item holds.
#pragma once

#include <string>

namespace voxgi {

// Throws InputError naming the file and the header line or element item that is malformed.
void checkPlyFile(const std::string& path);

}  // namespace voxgi
