// Log implementation: a replaceable sink, stderr by default.
#include "engine/Log.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace pacifica {
namespace {

LogSink& sinkRef() {
    static LogSink sink;
    return sink;
}

LogLevel initialLevel() {
    const char* env = std::getenv("PACIFICA_LOG");
    if (env && std::strcmp(env, "debug") == 0)
        return LogLevel::Debug;
    if (env && std::strcmp(env, "warning") == 0)
        return LogLevel::Warning;
    if (env && std::strcmp(env, "error") == 0)
        return LogLevel::Error;
    return LogLevel::Info;
}

LogLevel& levelRef() {
    static LogLevel level = initialLevel();
    return level;
}

const char* tag(LogLevel level) {
    switch (level) {
    case LogLevel::Debug:
        return "debug";
    case LogLevel::Info:
        return "info";
    case LogLevel::Warning:
        return "warning";
    case LogLevel::Error:
        return "error";
    }
    return "?";
}

} // namespace

void setLogSink(LogSink sink) {
    sinkRef() = std::move(sink);
}
void setLogLevel(LogLevel level) {
    levelRef() = level;
}

void log(LogLevel level, std::string_view message) {
    if (level < levelRef())
        return;
    if (sinkRef()) {
        sinkRef()(level, message);
        return;
    }
    std::fprintf(stderr, "[pacifica %s] %.*s\n", tag(level), static_cast<int>(message.size()),
                 message.data());
}

} // namespace pacifica
