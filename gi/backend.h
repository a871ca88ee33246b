// Where a technique computes: the CPU reference (TBB) or GL compute. One vocabulary, `cpu | gl`,
// for every method's `backend` setting and `--backend`.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace voxgi {

enum class Backend { Cpu, Gl };

inline std::vector<std::pair<std::string, Backend>> backendChoices() {
    return {{"cpu", Backend::Cpu}, {"gl", Backend::Gl}};
}

}  // namespace voxgi
