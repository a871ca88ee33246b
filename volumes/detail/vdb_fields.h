// A bounded little-endian reader over a .vdb file for the layout checks (vdb_structure.cpp,
// vdb_tree_walk.cpp): every read and skip must fit in the file, or InputError names the field
// and the byte.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "scenes/errors.h"

namespace voxgi::detail {

// A little-endian reader over the file that refuses to go past its end.
class VdbFields {
public:
    explicit VdbFields(const std::string& path) : path_(path), in_(path, std::ios::binary) {
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

}  // namespace voxgi::detail
