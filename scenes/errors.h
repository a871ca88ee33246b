// Errors from user input (files, fields, command-line values). The CLI prints the message on
// one line and exits with status 2.
#pragma once

#include <stdexcept>
#include <string>

namespace voxgi {

class InputError : public std::runtime_error {
public:
    explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// A feature that is named by the design but not built yet; the CLI exits with status 3.
class NotImplementedError : public std::runtime_error {
public:
    explicit NotImplementedError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace voxgi
