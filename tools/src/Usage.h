// Usage: what the CLI's option parsing shares -- the error for bad command-line input and the "WxH" size --
// used by the replay's options (Replay.h) and its view specs (ReplayInput.h) alike.
#pragma once

#include <stdexcept>
#include <string>

namespace pacifica::tools {

/// Bad command-line input (not a file's content): message names the option.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Parses "WxH" (e.g. "640x360", 16 <= W, H <= 8192); throws UsageError naming --size.
void parseSize(const std::string& text, int& width, int& height);

/// Frames first..last of a run, 0-based and inclusive (--frames I-J).
struct FrameRange {
    long long first = 0, last = 0;
};

/// Parses "I-J" (0 <= I <= J, decimal) or "I" (one frame); throws UsageError naming --frames.
FrameRange parseFrameRange(const std::string& text);

/// A name given on the command line (an OCIO view, a rig, an input image) as part of an output file name:
/// letters and digits lower-cased, anything else '-' ("ACES 1.0 - SDR Video" -> "aces-1-0---sdr-video").
std::string fileSlug(const std::string& name);

} // namespace pacifica::tools
