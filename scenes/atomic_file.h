// Files written whole or not at all, the one way every output of voxgi is written (EXR, PNG,
// .vdb, JSON, CSV, reports): the content goes to a temporary sibling that then replaces `path` by
// a rename, so a reader never sees half a file and a failed write leaves nothing behind.
#pragma once

#include <functional>
#include <string>

namespace voxgi {

// `write` fills the temporary file whose path it is given, throwing on failure. Errors (no such
// directory, a failed write, a failed rename) are InputError "<path>: cannot write (...)".
void writeFileAtomically(const std::string& path, const std::function<void(const std::string& temporary)>& write);
void writeTextAtomically(const std::string& path, const std::string& text);

}  // namespace voxgi
