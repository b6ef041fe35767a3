// BenchCli: the benchmarks' shared command line (CLI11): the --size validator (WxH, 16..8192 each, the
// same bounds as `pacifica replay --size`), one way to end on a bad argument (the program's name, the
// message, exit 2; --help exits 0) and the command line as it was typed for the reports. Reports are
// written with writeFileAtomically (engine/AtomicFile.h): every report file appears whole or not at all.
// Header-only.
#pragma once

#include "BenchText.h"
#include "engine/AtomicFile.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

namespace pacifica::bench {

/// Accepts "WxH" (bench::parseSize) and names the bounds otherwise.
inline CLI::Validator sizeValidator() {
    return CLI::Validator(
        [](std::string& s) {
            return parseSize(s) ? std::string()
                                : "expects WxH (16..8192 each), e.g. 1920x1080, got '" + s + "'";
        },
        "WxH");
}

/// Parses argv into `app`; on --help or a bad argument returns the exit code (0 or 2) after printing the
/// help or "PROGRAM: error: MESSAGE"; std::nullopt when the run goes on.
inline std::optional<int> parseCommandLine(CLI::App& app, int argc, char** argv) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "%s: error: %s\n", app.get_name().c_str(), e.what());
        return 2;
    }
    return std::nullopt;
}

/// The command line as typed, for report headers.
inline std::string commandLine(int argc, char** argv) {
    std::string s;
    for (int i = 0; i < argc; ++i)
        s += (i ? " " : "") + std::string(argv[i]);
    return s;
}

} // namespace pacifica::bench
