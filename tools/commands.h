// The voxgi CLI: one verb per file, registered at start-up. main.cpp holds the list of verbs
// the design names; a verb without a registered command reports "not implemented yet".
#pragma once

#include <string>
#include <vector>

namespace voxgi::cli {

// Exit statuses shared by every verb.
enum ExitCode { kOk = 0, kFailure = 1, kBadInput = 2, kNotImplemented = 3 };

using CommandFn = int (*)(const std::vector<std::string>& args);

struct Command {
    std::string name;
    std::string usage;  // one line: "voxgi render SCENE --method M -o OUT.exr ..."
    CommandFn run;
    std::string (*details)() = nullptr;  // more --help text made at run time (the method list)
};

bool registerCommand(const Command& command);
const Command* findCommand(const std::string& name);

}  // namespace voxgi::cli

#define VOXGI_REGISTER_COMMAND(name, usage, fn) \
    static const bool voxgi_registered_##fn = ::voxgi::cli::registerCommand({name, usage, fn})
#define VOXGI_REGISTER_COMMAND_WITH_DETAILS(name, usage, fn, details) \
    static const bool voxgi_registered_##fn = ::voxgi::cli::registerCommand({name, usage, fn, details})
