// Log: the engine's tiny logging facade. Messages go to stderr with a level tag; a host can install its
// own sink (e.g. to route into the game's console) with setLogSink().
#pragma once

#include <functional>
#include <string>
#include <string_view>

namespace pacifica {

enum class LogLevel { Debug, Info, Warning, Error };

using LogSink = std::function<void(LogLevel, std::string_view)>;

/// Replaces the sink (pass nullptr for the default stderr sink). Not thread-safe against concurrent logging.
void setLogSink(LogSink sink);
/// Messages below this level are dropped. Default Info; PACIFICA_LOG=debug lowers it.
void setLogLevel(LogLevel level);
void log(LogLevel level, std::string_view message);

inline void logDebug(std::string_view m) {
    log(LogLevel::Debug, m);
}
inline void logInfo(std::string_view m) {
    log(LogLevel::Info, m);
}
inline void logWarning(std::string_view m) {
    log(LogLevel::Warning, m);
}
inline void logError(std::string_view m) {
    log(LogLevel::Error, m);
}

} // namespace pacifica
