#include "scenes/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <random>
#include <utility>
#include <vector>

#include "scenes/errors.h"

namespace voxgi {

namespace fs = std::filesystem;

namespace {

// Temporary files that exist right now, for the signal handler: fixed slots of fixed size,
// claimed and released with atomics, so the handler reads them without locks or allocation.
constexpr int kSlots = 64;
constexpr std::size_t kPathMax = 4096;
struct Slot {
    std::atomic<bool> used{false};
    char path[kPathMax];
};
Slot gSlots[kSlots];

void removeTemporariesAndReraise(int signal) {
    for (Slot& s : gSlots)
        if (s.used.load()) ::unlink(s.path);  // async-signal-safe
    ::signal(signal, SIG_DFL);
    ::raise(signal);
}

void installHandlers() {
    static std::once_flag once;
    std::call_once(once, [] {
        for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
            struct sigaction old {};
            ::sigaction(sig, nullptr, &old);
            if (old.sa_handler != SIG_DFL) continue;  // someone else handles it (or ignores it)
            struct sigaction action {};
            action.sa_handler = removeTemporariesAndReraise;
            sigemptyset(&action.sa_mask);
            ::sigaction(sig, &action, nullptr);
        }
    });
}

std::atomic<bool> gClaimed[kSlots];  // claims come before `used`, so a slot is never seen half-written

// Registers a temporary file for removal on a signal while it exists.
class Tracked {
public:
    explicit Tracked(const std::string& path) {
        installHandlers();
        if (path.size() >= kPathMax) return;
        for (int i = 0; i < kSlots; ++i) {
            bool expected = false;
            if (!gClaimed[i].compare_exchange_strong(expected, true)) continue;
            std::memcpy(gSlots[i].path, path.c_str(), path.size() + 1);
            gSlots[i].used.store(true);
            slot_ = i;
            return;
        }
    }
    ~Tracked() {
        if (slot_ < 0) return;
        gSlots[slot_].used.store(false);
        gClaimed[slot_].store(false);
    }
    Tracked(Tracked&& other) noexcept : slot_(std::exchange(other.slot_, -1)) {}
    Tracked& operator=(Tracked&&) = delete;
    Tracked(const Tracked&) = delete;

private:
    int slot_ = -1;
};

struct Pending {
    std::string temporary, target, shown;
    Tracked tracked;
};

struct Batch {
    std::vector<Pending> pending;
};

std::mutex gBatchMutex;
OutputBatch* gOpen = nullptr;  // the open batch, if any
Batch* gOpenState = nullptr;

void flushToDisk(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY);
    if (fd < 0) throw std::runtime_error(std::string("cannot reopen to flush: ") + std::strerror(errno));
    const int rc = ::fsync(fd);
    ::close(fd);
    if (rc != 0) throw std::runtime_error(std::string("fsync failed: ") + std::strerror(errno));
}

void renameInto(const std::string& temporary, const std::string& target, const std::string& shown) {
    std::error_code ec;
    fs::rename(temporary, target, ec);
    if (ec) {
        const std::string why = ec.message();
        fs::remove(temporary, ec);
        throw InputError(shown + ": cannot write (" + why + ")");
    }
}

}  // namespace

std::string outputTarget(const std::string& path) {
    std::error_code ec;
    fs::path p(path);
    // Follow symlinks to the file they name (the link itself stays); a dangling link names the
    // file it would create.
    for (int hops = 0; fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
        if (hops > 32) throw InputError(path + ": too many levels of symbolic links");
        fs::path to = fs::read_symlink(p, ec);
        if (ec) throw InputError(path + ": cannot read the symbolic link (" + ec.message() + ")");
        p = to.is_absolute() ? to : p.parent_path() / to;
    }
    const fs::file_status st = fs::status(p, ec);
    if (fs::exists(st) && !fs::is_regular_file(st))
        throw InputError(path + ": " + (fs::is_directory(st) ? "is a directory" : "is not a regular file") +
                         " (voxgi writes only regular files)");
    return p.string();
}

void writeFileAtomically(const std::string& path, const std::function<void(const std::string& temporary)>& write) {
    const std::string target = outputTarget(path);
    const fs::path parent = fs::path(target).parent_path();
    if (!parent.empty() && !fs::is_directory(parent)) throw InputError(path + ": output directory does not exist");
    std::random_device rd;
    const std::string temporary =
        (parent / ("." + fs::path(target).filename().string() + ".tmp" + std::to_string(rd() % 1000000))).string();
    Tracked tracked(temporary);
    std::error_code ec;
    try {
        write(temporary);
        flushToDisk(temporary);
    } catch (const std::exception& e) {
        fs::remove(temporary, ec);
        throw InputError(path + ": cannot write (" + e.what() + ")");
    }
    {
        std::lock_guard<std::mutex> lock(gBatchMutex);
        if (gOpenState) {
            gOpenState->pending.push_back({temporary, target, path, std::move(tracked)});
            return;
        }
    }
    renameInto(temporary, target, path);
}

void writeTextAtomically(const std::string& path, const std::string& text) {
    writeFileAtomically(path, [&](const std::string& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        out << text;
        out.close();
        if (!out) throw std::runtime_error("write failed");
    });
}

OutputBatch::OutputBatch() {
    std::lock_guard<std::mutex> lock(gBatchMutex);
    if (gOpen) throw std::logic_error("OutputBatch: one batch at a time");
    gOpen = this;
    gOpenState = new Batch;
}

OutputBatch::~OutputBatch() {
    std::lock_guard<std::mutex> lock(gBatchMutex);
    if (gOpen != this) return;
    std::error_code ec;
    if (gOpenState)
        for (Pending& p : gOpenState->pending) fs::remove(p.temporary, ec);
    delete gOpenState;
    gOpenState = nullptr;
    gOpen = nullptr;
}

void OutputBatch::commit() {
    std::vector<Pending> pending;
    {
        std::lock_guard<std::mutex> lock(gBatchMutex);
        if (gOpen != this || !gOpenState) return;
        pending.swap(gOpenState->pending);
    }
    for (std::size_t i = 0; i < pending.size(); ++i) {
        try {
            renameInto(pending[i].temporary, pending[i].target, pending[i].shown);
        } catch (...) {
            std::error_code ec;
            for (std::size_t j = i + 1; j < pending.size(); ++j) fs::remove(pending[j].temporary, ec);
            throw;
        }
    }
}

OutputBatch::Immediate::Immediate() {
    // Park the open batch's state: writes go straight into place until this scope ends.
    std::lock_guard<std::mutex> lock(gBatchMutex);
    suspended_ = gOpenState;
    gOpenState = nullptr;
}

OutputBatch::Immediate::~Immediate() {
    std::lock_guard<std::mutex> lock(gBatchMutex);
    if (gOpen) gOpenState = static_cast<Batch*>(suspended_);
}

}  // namespace voxgi
