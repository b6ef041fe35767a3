// AtomicFile: a file appears whole or not at all. The text is written to a hidden temporary beside the
// target (same directory, so the same filesystem), flushed, and renamed over the target; on any failure the
// temporary is removed and the target is left as it was. Every tool, bench and the game write their
// summaries and reports through it, so an interrupted run never leaves a half-written file behind.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

namespace pacifica {

/// Writes `text` to `path` atomically. Throws std::runtime_error "PATH: cannot write: REASON" (the target
/// untouched, no temporary left) when the directory is missing or read-only, the disk is full, or the
/// rename fails.
void writeFileAtomically(const std::filesystem::path& path, std::string_view text);

/// The same, with the contents streamed by `write` (which may throw: the temporary is removed and the
/// exception passes through).
void writeFileAtomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);

} // namespace pacifica
