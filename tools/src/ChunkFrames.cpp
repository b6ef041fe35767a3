// ChunkFrames: a sharded replay chunk's frames, landed and kept (ChunkFrames.h).
#include "ChunkFrames.h"

#include "engine/capture/Capture.h"

#include <cinttypes>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace pacifica::tools {
namespace fs = std::filesystem;

std::string hex64(uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016" PRIx64, v);
    return buf;
}

std::string sidecarName(const std::string& frameBase) {
    return frameBase + ".check.json";
}

std::string chunkSummaryName(const FrameRange& range) {
    char name[64];
    std::snprintf(name, sizeof name, "chunk-%05lld-%05lld.json", range.first, range.last);
    return name;
}

std::vector<std::string> entryFiles(const nlohmann::json& entry) {
    std::vector<std::string> names;
    for (const char* key : {"exr", "png"})
        if (entry.contains(key) && entry[key].is_string())
            names.push_back(entry[key].get<std::string>());
    if (entry.contains("extra_views") && entry["extra_views"].is_array())
        for (const nlohmann::json& e : entry["extra_views"])
            if (e.contains("png") && e["png"].is_string())
                names.push_back(e["png"].get<std::string>());
    return names;
}

std::string sidecarText(const fs::path& dir, const std::string& runKey, const nlohmann::json& entry) {
    nlohmann::json files = nlohmann::json::object();
    for (const std::string& name : entryFiles(entry)) {
        const std::optional<uint64_t> h = capture::hashFileBytes(dir / name);
        if (!h)
            throw std::runtime_error((dir / name).string() + ": cannot read back the frame just written");
        files[name] = hex64(*h);
    }
    return nlohmann::json{{"run_key", runKey}, {"files", std::move(files)}, {"frame", entry}}.dump(1) + "\n";
}

std::optional<nlohmann::json> keptFrame(const fs::path& dir, const std::string& frameBase,
                                        const std::string& runKey) {
    std::ifstream in(dir / sidecarName(frameBase));
    if (!in)
        return std::nullopt;
    const nlohmann::json s = nlohmann::json::parse(in, nullptr, false);
    if (s.is_discarded() || !s.is_object() || s.value("run_key", std::string()) != runKey ||
        !s.contains("files") || !s["files"].is_object() || !s.contains("frame") || !s["frame"].is_object())
        return std::nullopt;
    const std::vector<std::string> names = entryFiles(s["frame"]);
    if (names.size() != s["files"].size())
        return std::nullopt;
    for (const std::string& name : names) {
        if (!s["files"].contains(name) || !s["files"][name].is_string() ||
            name.find('/') != std::string::npos)
            return std::nullopt;
        const std::optional<uint64_t> h = capture::hashFileBytes(dir / name);
        if (!h || hex64(*h) != s["files"][name].get<std::string>())
            return std::nullopt;
    }
    return s["frame"];
}

} // namespace pacifica::tools
