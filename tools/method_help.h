// The method list as the CLI's --help texts show it, made from the method declarations.
#pragma once

#include <string>

namespace voxgi::cli {

// One line per method (name, summary; planned ones marked) and where to find its settings.
std::string methodList();
// methodList() plus each built method's main settings with their defaults and ranges.
std::string methodListWithSettings();

}  // namespace voxgi::cli
