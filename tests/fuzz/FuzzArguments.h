// FuzzArguments: a fuzz input as a command line -- the bytes split at newlines into arguments (at most 64),
// what the command-line fuzzers (fuzz_game_options, fuzz_tool_options) feed their parsers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pacifica::fuzz {

inline std::vector<std::string> splitArguments(const uint8_t* data, size_t size) {
    std::vector<std::string> args;
    std::string arg;
    for (size_t i = 0; i < size && args.size() < 64; ++i) {
        if (data[i] == '\n') {
            args.push_back(arg);
            arg.clear();
        } else {
            arg.push_back(static_cast<char>(data[i]));
        }
    }
    if (!arg.empty() && args.size() < 64)
        args.push_back(arg);
    return args;
}

} // namespace pacifica::fuzz
