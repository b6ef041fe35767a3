// ChunkFrames: how a chunk of a sharded replay (ReplayOptions::frames, docs/SCALE.md) lands its frames and
// knows them again. Each view frame's files (EXR, PNG, the extra views' PNGs) are renamed into the output
// folder, then its sidecar NAME.check.json is written atomically: the run's key, the XXH64 of every file's
// bytes, and the frame's summary entry. A later run of the same chunk keeps a frame whose sidecar names its
// key and whose files all still have those checksums, and takes its summary entry from the sidecar.
#pragma once

#include "Usage.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace pacifica::tools {

/// A 64-bit hash as 16 lower-case hex digits (the summaries' and sidecars' XXH64s).
std::string hex64(uint64_t v);

/// "frame_00012" -> "frame_00012.check.json".
std::string sidecarName(const std::string& frameBase);

/// "chunk-00000-00099.json": a chunk's summary beside the frames.
std::string chunkSummaryName(const FrameRange& range);

/// The files a view frame's summary entry names: "exr", "png" and every extra view's "png".
std::vector<std::string> entryFiles(const nlohmann::json& entry);

/// The sidecar of a view frame whose files are in `dir`: {"run_key", "files": {name: XXH64 hex}, "frame"}.
/// Throws std::runtime_error naming a file that cannot be read back.
std::string sidecarText(const std::filesystem::path& dir, const std::string& runKey,
                        const nlohmann::json& entry);

/// The summary entry of a view frame an earlier run left whole: DIR/sidecarName(base) parses, names runKey,
/// and every file it lists exists with its checksum. std::nullopt otherwise (the frame is rendered again).
std::optional<nlohmann::json> keptFrame(const std::filesystem::path& dir, const std::string& frameBase,
                                        const std::string& runKey);

} // namespace pacifica::tools
