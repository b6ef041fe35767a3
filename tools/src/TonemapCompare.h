// `pacifica tonemap compare INPUT... --out DIR`: shows, side by side and in numbers, what each display
// transform does to the same scene-linear frames (issue: HDR tonemapping comparisons; docs/TONEMAP.md).
//
// Inputs: scene-linear EXRs (any size; RGB or RGBA; NaN/Inf counted and replaced before transforming), a
// replay output folder (its summary.json; up to --frames of its EXRs), a flight file (rendered first by the
// replay into DIR/renders/), and always the generated test chart. LDR images are read with a warning.
// Transforms: every view of every sRGB display of the embedded config, of $OCIO and of each --ocio-config,
// plus the shipped closed-form tonemappers as a generated OCIO config (tonemap/ConfigWriter.h).
// Output (written into a staging folder and moved into DIR only when complete): sheets/<input>.png contact
// sheets with labels, and per input an exposure bracket (-4..+4 EV) per transform, false colour of the
// source in stops, per-channel histograms per transform, a wipe and a difference between two transforms;
// metrics.json, report.md, report.html (self-contained), ocio/ (the generated config).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace pacifica::tools {

struct TonemapCompareOptions {
    std::vector<std::string> inputs;
    std::filesystem::path outDir;
    std::vector<std::filesystem::path> ocioConfigs; ///< --ocio-config, repeatable
    int lut3dSize = 33;                             ///< PBR Neutral's cube in the shipped config
    long long maxPixels = 50'000'000;               ///< larger images are refused, naming their size
    int tileWidth = 360;                            ///< contact-sheet tile width in pixels
    int framesPerFolder = 3;                        ///< EXRs taken from a replay folder, evenly spaced
    /// --pair A,B: the two transforms of the wipe and difference sheets, each a case-insensitive part of
    /// a transform's label that names exactly one.
    std::string pair = "pacifica: AgX base,embedded: sRGB / ACES 1.0 - SDR Video";
    /// Run every transform on the GPU too (OCIO's GLSL through color::Tonemapper, headless EGL) and report
    /// its largest difference from the CPU processor; without a GL context this is a warning.
    bool gpu = true;
};

/// Runs the comparison. Throws std::runtime_error naming the input, option or file at fault; nothing is
/// left in DIR then.
void runTonemapCompare(const TonemapCompareOptions& options);

} // namespace pacifica::tools
