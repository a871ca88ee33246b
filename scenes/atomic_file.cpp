#include "scenes/atomic_file.h"

#include <filesystem>
#include <fstream>
#include <random>

#include "scenes/errors.h"

namespace voxgi {

namespace fs = std::filesystem;

void writeFileAtomically(const std::string& path, const std::function<void(const std::string& temporary)>& write) {
    const fs::path parent = fs::path(path).parent_path();
    if (!parent.empty() && !fs::is_directory(parent)) throw InputError(path + ": output directory does not exist");
    std::random_device rd;
    const std::string temporary =
        (parent / ("." + fs::path(path).filename().string() + ".tmp" + std::to_string(rd() % 1000000))).string();
    std::error_code ec;
    try {
        write(temporary);
    } catch (const std::exception& e) {
        fs::remove(temporary, ec);
        throw InputError(path + ": cannot write (" + e.what() + ")");
    }
    fs::rename(temporary, path, ec);
    if (ec) {
        const std::string why = ec.message();
        fs::remove(temporary, ec);
        throw InputError(path + ": cannot write (" + why + ")");
    }
}

void writeTextAtomically(const std::string& path, const std::string& text) {
    writeFileAtomically(path, [&](const std::string& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        out << text;
        out.close();
        if (!out) throw std::runtime_error("write failed");
    });
}

}  // namespace voxgi
