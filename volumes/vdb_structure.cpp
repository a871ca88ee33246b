#include "volumes/vdb_structure.h"

#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "scenes/errors.h"

namespace voxgi {

namespace {

// A little-endian reader over the file that refuses to go past its end.
class Fields {
public:
    Fields(const std::string& path) : path_(path), in_(path, std::ios::binary) {
        std::error_code ec;
        size_ = std::uint64_t(std::filesystem::file_size(path, ec));
        if (ec || !in_) fail("cannot read the file");
    }
    [[noreturn]] void fail(const std::string& why) const {
        throw InputError(path_ + ": not a readable .vdb file (" + why + " at byte " + std::to_string(position_) + ")");
    }
    std::uint64_t left() const { return size_ - position_; }
    std::uint64_t position() const { return position_; }
    void bytes(void* out, std::uint64_t n, const char* what) {
        if (n > left()) fail(std::string(what) + " runs past the end of the file");
        in_.read(static_cast<char*>(out), std::streamsize(n));
        if (!in_) fail(std::string("cannot read ") + what);
        position_ += n;
    }
    template <typename T>
    T value(const char* what) {
        T v{};
        bytes(&v, sizeof v, what);
        return v;
    }
    // A length-prefixed string (OpenVDB's readString), its length bounded by the file.
    std::string text(const char* what) {
        const std::uint32_t n = value<std::uint32_t>(what);
        if (n > left()) fail(std::string(what) + " of " + std::to_string(n) + " bytes runs past the end of the file");
        std::string s(n, '\0');
        bytes(s.data(), n, what);
        return s;
    }
    void skip(std::uint64_t n, const char* what) {
        if (n > left()) fail(std::string(what) + " of " + std::to_string(n) + " bytes runs past the end of the file");
        in_.seekg(std::streamoff(n), std::ios::cur);
        position_ += n;
    }
    void seek(std::uint64_t to, const char* what) {
        if (to > size_) fail(std::string(what) + " points past the end of the file");
        in_.clear();
        in_.seekg(std::streamoff(to));
        position_ = to;
    }
    std::uint64_t size() const { return size_; }

private:
    std::string path_;
    std::ifstream in_;
    std::uint64_t size_ = 0, position_ = 0;
};

constexpr std::uint32_t kFirstCheckedVersion = 220;  // files with a text UUID in the header
constexpr std::uint32_t kGridInstancingVersion = 217;

bool isUuid(const char* s) {
    for (int i = 0; i < 36; ++i) {
        const bool dash = i == 8 || i == 13 || i == 18 || i == 23;
        if (dash ? s[i] != '-' : !std::isxdigit(static_cast<unsigned char>(s[i]))) return false;
    }
    return true;
}

}  // namespace

void checkVdbStructure(const std::string& path) {
    Fields f(path);
    unsigned char magic[8] = {};
    const unsigned char expected[8] = {0x20, 0x42, 0x44, 0x56, 0, 0, 0, 0};  // 0x56444220, "VDB "
    if (f.left() < 8) throw InputError(path + ": not a .vdb file (no OpenVDB header)");
    f.bytes(magic, 8, "magic number");
    if (std::memcmp(magic, expected, 8) != 0) throw InputError(path + ": not a .vdb file (no OpenVDB header)");
    const std::uint32_t version = f.value<std::uint32_t>("file version");
    if (version < kFirstCheckedVersion) return;  // older layouts: OpenVDB alone decides
    f.value<std::uint32_t>("library major version");
    f.value<std::uint32_t>("library minor version");
    const char hasOffsets = f.value<char>("grid offsets flag");
    char uuid[36];
    f.bytes(uuid, 36, "file UUID");
    if (!isUuid(uuid)) f.fail("corrupt file UUID");
    // File metadata: name, type name, then the value's byte count and bytes.
    const std::int32_t metadata = f.value<std::int32_t>("metadata count");
    if (metadata < 0 || std::uint64_t(metadata) * 12 > f.left()) f.fail("metadata count " + std::to_string(metadata));
    for (std::int32_t i = 0; i < metadata; ++i) {
        f.text("metadata name");
        f.text("metadata type name");
        f.skip(f.value<std::uint32_t>("metadata size"), "metadata value");
    }
    if (!hasOffsets) return;  // streamed files: grids follow without descriptors
    const std::int32_t grids = f.value<std::int32_t>("grid count");
    if (grids < 0 || std::uint64_t(grids) * 36 > f.left()) f.fail("grid count " + std::to_string(grids));
    for (std::int32_t i = 0; i < grids; ++i) {
        f.text("grid name");
        f.text("grid type");
        if (version >= kGridInstancingVersion) f.text("grid instance parent");
        const std::int64_t grid = f.value<std::int64_t>("grid position"), block = f.value<std::int64_t>("block position"),
                           end = f.value<std::int64_t>("grid end position");
        if (!(std::uint64_t(grid) == f.position() && grid <= block && block <= end && std::uint64_t(end) <= f.size()))
            f.fail("grid " + std::to_string(i) + " offsets " + std::to_string(grid) + ", " + std::to_string(block) + ", " +
                   std::to_string(end) + " do not fit the file");
        f.seek(std::uint64_t(end), "grid end position");
    }
}

}  // namespace voxgi
