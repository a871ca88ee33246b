// Files written whole or not at all, the one way every output of voxgi is written (EXR, PNG,
// .vdb, JSON, CSV, reports): the content goes to a temporary sibling, is flushed to disk, and
// then replaces `path` by a rename, so a reader never sees half a file and a failed write leaves
// nothing behind. A symlink at `path` is followed (its target is replaced, the link stays); a
// directory, FIFO or device there is refused.
//
// While an OutputBatch is open (the CLI opens one per command), renames wait for its commit():
// a command's outputs appear together or not at all. Temporary files are removed if the process
// is interrupted (SIGINT, SIGTERM, SIGHUP) while they exist.
#pragma once

#include <functional>
#include <string>

namespace voxgi {

// `write` fills the temporary file whose path it is given, throwing on failure. Errors (no such
// directory, a failed write, a failed rename) are InputError "<path>: cannot write (...)".
void writeFileAtomically(const std::string& path, const std::function<void(const std::string& temporary)>& write);
void writeTextAtomically(const std::string& path, const std::string& text);

// The file a write to `path` replaces: `path`, or the target of the symlink(s) at `path`.
// InputError when something other than a regular file (or nothing) is there.
std::string outputTarget(const std::string& path);

class OutputBatch {
public:
    OutputBatch();
    // Without commit(), every file written under the batch is removed.
    ~OutputBatch();
    OutputBatch(const OutputBatch&) = delete;
    OutputBatch& operator=(const OutputBatch&) = delete;
    // Renames every file written under the batch into place, in the order written.
    void commit();

    // Writes under its scope go straight into place even inside a batch (caches, not outputs).
    class Immediate {
    public:
        Immediate();
        ~Immediate();
        Immediate(const Immediate&) = delete;
        Immediate& operator=(const Immediate&) = delete;

    private:
        void* suspended_;  // the open batch's state, parked
    };
};

}  // namespace voxgi
