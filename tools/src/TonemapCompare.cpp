// `pacifica tonemap compare` (TonemapCompare.h).
#include "TonemapCompare.h"

#include "FlightPath.h"
#include "OutputTransaction.h"
#include "Replay.h"

#include <engine/AtomicFile.h>
#include <engine/capture/Capture.h>
#include <engine/color/ColorPipeline.h>
#include <engine/color/Tonemapper.h>
#include <engine/gl/GlContext.h>
#include <engine/gl/GlObjects.h>
#include <recording/Recording.h>
#include <tonemap/ConfigWriter.h>
#include <tonemap/Curves.h>
#include <tonemap/Metrics.h>
#include <tonemap/Sheets.h>
#include <tonemap/TextRender.h>

#include <epoxy/gl.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

namespace pacifica::tools {

namespace fs = std::filesystem;
using color::ColorPipeline;
using json = nlohmann::json;
namespace tm = pacifica::tonemap;

namespace {

struct Input {
    std::string name;   ///< label and file stem
    std::string source; ///< where it came from
    int width = 0, height = 0;
    std::vector<float> rgb; ///< scene-linear, non-finite values replaced
    tm::SourceCensus census;
    bool ldr = false;
    bool chart = false;
};

struct Transform {
    std::string label;  ///< "config: display / view"
    std::string config; ///< config label
    std::string display, view;
    std::string tonemapperId; ///< closed-form tonemapper this view ships, if any
    ColorPipeline pipeline;
    /// How its code values become display-linear light for the colour metrics: through the display colour
    /// space back to CIE XYZ (ColorPipeline::decodeDisplayCpu), else the sRGB EOTF.
    bool decodesToXyz = false;
};

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

/// NaN -> 0, +Inf -> 65504 (the largest half), -Inf -> 0: what the transforms see (the census counts them).
void sanitise(std::vector<float>& rgb) {
    for (float& v : rgb)
        if (std::isnan(v) || v == -INFINITY)
            v = 0.0f;
        else if (v == INFINITY)
            v = 65504.0f;
}

Input fromImage(const fs::path& file, const std::string& name, long long maxPixels) {
    capture::Image img;
    try {
        img = capture::readImage(file);
    } catch (const std::exception& e) {
        throw std::runtime_error(file.string() + ": not an image this tool reads (" + e.what() + ")");
    }
    const long long pixels = static_cast<long long>(img.width) * img.height;
    if (pixels > maxPixels)
        throw std::runtime_error(file.string() + ": " + std::to_string(img.width) + "x" +
                                 std::to_string(img.height) + " = " + std::to_string(pixels) +
                                 " pixels is over the limit of " + std::to_string(maxPixels) +
                                 " (--max-pixels)");
    if (img.channels < 3)
        throw std::runtime_error(file.string() + ": has " + std::to_string(img.channels) +
                                 " channel(s); RGB or RGBA is needed");
    Input in;
    in.name = name;
    in.source = file.string();
    in.width = img.width;
    in.height = img.height;
    in.rgb.resize(static_cast<size_t>(pixels) * 3);
    for (size_t i = 0; i < static_cast<size_t>(pixels); ++i)
        for (size_t k = 0; k < 3; ++k)
            in.rgb[3 * i + k] = img.pixels[i * static_cast<size_t>(img.channels) + k];
    in.census = tm::census(in.rgb.data(), static_cast<size_t>(pixels));
    sanitise(in.rgb);
    const std::string ext = lower(file.extension().string());
    in.ldr =
        ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".gif" || ext == ".webp";
    if (in.ldr)
        std::fprintf(stderr,
                     "pacifica: warning: %s is a display-referred (LDR) image, not scene-linear: "
                     "its transforms are compared as if it were\n",
                     file.c_str());
    return in;
}

std::vector<fs::path> replayFrames(const fs::path& dir, int count) {
    std::vector<fs::path> exrs;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file() && lower(e.path().extension().string()) == ".exr")
            exrs.push_back(e.path());
    std::sort(exrs.begin(), exrs.end());
    if (exrs.empty())
        throw std::runtime_error(dir.string() +
                                 ": a replay folder without EXR frames (was it run with --no-images?)");
    std::vector<fs::path> picked;
    const int n = std::min<int>(count, static_cast<int>(exrs.size()));
    for (int i = 0; i < n; ++i) {
        const size_t k = n == 1 ? exrs.size() / 2
                                : static_cast<size_t>(i) * (exrs.size() - 1) / static_cast<size_t>(n - 1);
        picked.push_back(exrs[k]);
    }
    return picked;
}

/// A flight file rendered by the replay into `renderDir`: up to `frames` frames over the flight.
std::vector<fs::path> renderFlight(const fs::path& flight, const fs::path& renderDir, int frames) {
    ReplayOptions r;
    r.flight = flight;
    r.outDir = renderDir;
    r.progress = false;
    double span = 0.0;
    const std::string format = recording::detectFormat(flight);
    if (format == "csv") {
        const FlightPath p = FlightPath::load(flight);
        span = p.endTime() - p.startTime();
    } else {
        const recording::Recording rec = recording::readRecording(flight);
        span = rec.endTime - rec.startTime;
    }
    // floor(span * fps) + 1 frames: half a frame of slack keeps rounding from dropping the last one.
    r.fps = frames > 1 && span > 0.0 ? (static_cast<double>(frames) - 0.5) / span : 1.0;
    std::fprintf(stderr, "pacifica: rendering %s (%d frames) into %s\n", flight.c_str(), frames,
                 renderDir.c_str());
    runReplay(r);
    return replayFrames(renderDir, frames);
}

std::vector<float> toRgba(const std::vector<float>& rgb) {
    const size_t n = rgb.size() / 3;
    std::vector<float> rgba(n * 4);
    for (size_t i = 0; i < n; ++i) {
        for (size_t k = 0; k < 3; ++k)
            rgba[4 * i + k] = rgb[3 * i + k];
        rgba[4 * i + 3] = 1.0f;
    }
    return rgba;
}

std::vector<float> applyTransform(const Transform& t, const std::vector<float>& rgb) {
    std::vector<float> rgba = toRgba(rgb);
    t.pipeline.applyCpu(rgba.data(), rgba.size() / 4);
    std::vector<float> out(rgb.size());
    for (size_t i = 0; i < rgb.size() / 3; ++i)
        for (size_t k = 0; k < 3; ++k) {
            const float v = rgba[4 * i + k];
            out[3 * i + k] = std::isfinite(v) ? v : 0.0f;
        }
    return out;
}

std::string base64(const std::string& bytes) {
    static const char* A = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                           (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                           static_cast<unsigned char>(bytes[i + 2]);
        out += {A[v >> 18], A[(v >> 12) & 63], A[(v >> 6) & 63], A[v & 63]};
    }
    if (i + 1 == bytes.size()) {
        const unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
        out += {A[v >> 18], A[(v >> 12) & 63], '=', '='};
    } else if (i + 2 == bytes.size()) {
        const unsigned v =
            (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8);
        out += {A[v >> 18], A[(v >> 12) & 63], A[(v >> 6) & 63], '='};
    }
    return out;
}

std::string fmt(double v, int precision = 3) {
    char b[64];
    std::snprintf(b, sizeof b, "%.*f", precision, v);
    return b;
}

/// Adds every view of every sRGB display of `pipeline`; other displays are listed in `skipped`.
void addConfigViews(const ColorPipeline& pipeline, const std::string& configLabel,
                    std::vector<Transform>& out, std::vector<std::string>& skipped) {
    for (const std::string& d : pipeline.displays()) {
        for (const std::string& v : pipeline.views(d)) {
            Transform t{configLabel + ": " + d + " / " + v, configLabel, d, v, "", pipeline};
            t.pipeline.select(d, v);
            // A view that passes scene-linear values through unchanged (a data / "Raw" view) is no display
            // transform: its metrics would mean nothing.
            float probe[8] = {0.18f, 2.0f, 0.05f, 1.0f, 0.5f, 0.5f, 0.5f, 1.0f};
            t.pipeline.applyCpu(probe, 2);
            if (std::fabs(probe[0] - 0.18f) < 1e-6f && std::fabs(probe[1] - 2.0f) < 1e-6f &&
                std::fabs(probe[2] - 0.05f) < 1e-6f) {
                skipped.push_back(t.label + " (passes scene-linear data through: no display transform)");
                continue;
            }
            float none[4] = {0, 0, 0, 1};
            t.decodesToXyz = t.pipeline.decodeDisplayCpu(none, 0);
            if (!t.decodesToXyz && lower(d).find("srgb") == std::string::npos) {
                skipped.push_back(t.label + " (its view names no display colour space and the display is not "
                                            "sRGB: its code values cannot be decoded)");
                continue;
            }
            out.push_back(std::move(t));
        }
    }
}

json metricsJson(const tm::TransformMetrics& m) {
    return {{"pixels", m.pixels},
            {"clipped", m.clipped},
            {"crushed", m.crushed},
            {"chromatic_pixels", m.chromatic},
            {"desaturated_to_neutral", m.desaturated},
            {"hue_shift_mean_deg", m.hueShiftMean},
            {"hue_shift_p95_deg", m.hueShiftP95},
            {"chroma_ratio", m.chromaRatio},
            {"contrast_kept", m.contrastKept},
            {"neutral_drift", m.neutralDrift},
            {"non_finite_output", m.nonFiniteOutput}};
}

/// Staging folder inside the output's parent, moved into place at the end (never a half-written DIR).
class Staging {
public:
    explicit Staging(fs::path out) : mOut(std::move(out)) {
        const fs::path parent = mOut.parent_path().empty() ? fs::path(".") : mOut.parent_path();
        fs::create_directories(parent);
        mDir = parent / ("." + mOut.filename().string() + ".staging-" + std::to_string(getpid()));
        fs::remove_all(mDir);
        fs::create_directories(mDir);
    }
    ~Staging() {
        std::error_code ec;
        if (!mCommitted)
            fs::remove_all(mDir, ec);
    }
    const fs::path& dir() const { return mDir; }
    void commit() {
        fs::create_directories(mOut);
        for (const auto& e : fs::directory_iterator(mDir)) {
            const fs::path target = mOut / e.path().filename();
            std::error_code ec;
            fs::remove_all(target, ec);
            fs::rename(e.path(), target);
        }
        fs::remove_all(mDir);
        mCommitted = true;
    }

private:
    fs::path mOut, mDir;
    bool mCommitted = false;
};

/// The GPU path: OCIO's GLSL for each transform (color::Tonemapper, LUT textures included) on a headless GL
/// context, read back to compare with the CPU processor. Built lazily per transform; absent without GL.
class GpuCheck {
public:
    GpuCheck(size_t transforms, bool enabled) : mPasses(transforms) {
        if (!enabled)
            return;
        try {
            mContext = gl::createHeadlessContext();
            mRenderer = mContext->info().renderer;
        } catch (const std::exception& e) {
            std::fprintf(stderr,
                         "pacifica: warning: no GL context (%s): GPU-vs-CPU differences are not measured\n",
                         e.what());
        }
    }
    bool available() const { return mContext != nullptr; }
    const std::string& renderer() const { return mRenderer; }

    /// Tonemaps `rgb` (w x h) with transform `ti` on the GPU; returns the code values (RGB).
    std::vector<float> run(size_t ti, const Transform& t, const std::vector<float>& rgb, int w, int h) {
        if (!mPasses[ti])
            mPasses[ti] = std::make_unique<color::Tonemapper>(t.pipeline);
        if (w != mWidth || h != mHeight) {
            mScene = gl::Texture::create2D(GL_RGBA32F, w, h);
            mTarget = gl::Texture::create2D(GL_RGBA32F, w, h);
            mFbo = gl::Framebuffer::create();
            mFbo.attachColor(0, mTarget);
            mFbo.checkComplete("tonemap compare target");
            mWidth = w;
            mHeight = h;
        }
        if (&rgb != mUploaded || rgb.size() != mUploadedSize) {
            const std::vector<float> rgba = toRgba(rgb);
            glTextureSubImage2D(mScene.id(), 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, rgba.data());
            mUploaded = &rgb;
            mUploadedSize = rgb.size();
        }
        mPasses[ti]->run(mScene, mFbo, w, h);
        std::vector<float> rgba(static_cast<size_t>(w) * static_cast<size_t>(h) * 4);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, mFbo.id());
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, rgba.data());
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        std::vector<float> out(rgb.size());
        for (size_t i = 0; i < out.size() / 3; ++i)
            for (size_t k = 0; k < 3; ++k)
                out[3 * i + k] = rgba[4 * i + k];
        return out;
    }

private:
    std::unique_ptr<gl::GlContext> mContext;
    std::string mRenderer;
    std::vector<std::unique_ptr<color::Tonemapper>> mPasses;
    gl::Texture mScene, mTarget;
    gl::Framebuffer mFbo;
    int mWidth = 0, mHeight = 0;
    const std::vector<float>* mUploaded = nullptr;
    size_t mUploadedSize = 0;
};

/// Display-linear Rec.709 light of a transform's code values (scale: relative for SDR, 1 = 100 cd/m^2 for
/// the ACES configs' HDR displays; the colour metrics are scale-free).
std::vector<float> displayLinear(const Transform& t, const std::vector<float>& code) {
    std::vector<float> out(code.size());
    if (!t.decodesToXyz) {
        for (size_t i = 0; i < code.size(); ++i)
            out[i] = tm::srgbDecode(code[i]);
        return out;
    }
    std::vector<float> rgba = toRgba(code);
    for (float& v : rgba) // what a display shows: code values outside [0, 1] are clipped by it
        v = std::clamp(v, 0.0f, 1.0f);
    t.pipeline.decodeDisplayCpu(rgba.data(), rgba.size() / 4);
    for (size_t i = 0; i < code.size() / 3; ++i)
        for (size_t k = 0; k < 3; ++k)
            out[3 * i + k] = rgba[4 * i + k];
    tm::xyzToLinearRec709(out.data(), out.size() / 3);
    return out;
}

/// hdr/<input>-pq.png (16-bit Rec.2100 PQ code values, Rec.2020 primaries) and hdr/<input>-nits.exr (the
/// same pixels as absolute luminance in cd/m^2, PQ-decoded) through the ACES 1.1 HDR 1000 cd/m^2 view;
/// returns its numbers: peak, share of pixels at the 1000 cd/m^2 peak (any channel >= 990), and where 0.18
/// lands.
json hdrOutput(const fs::path& dir, const Input& in, const ColorPipeline& hdr, const std::string& view,
               const tm::Chart* chart) {
    std::vector<float> rgba = toRgba(in.rgb);
    hdr.applyCpu(rgba.data(), rgba.size() / 4);
    const size_t n = rgba.size() / 4;
    std::vector<float> code(n * 3), nits(n * 3);
    double peak = 0.0;
    size_t atPeak = 0;
    for (size_t i = 0; i < n; ++i) {
        bool top = false;
        for (size_t k = 0; k < 3; ++k) {
            const float c = std::isfinite(rgba[4 * i + k]) ? rgba[4 * i + k] : 0.0f;
            code[3 * i + k] = c;
            nits[3 * i + k] = tm::pqDecode(c);
            peak = std::max(peak, static_cast<double>(nits[3 * i + k]));
            top = top || nits[3 * i + k] >= 990.0f;
        }
        atPeak += top;
    }
    capture::writePng16(dir / (in.name + "-pq.png"), in.width, in.height, 3, code.data());
    capture::Metadata meta;
    meta.strings = {{"units", "cd/m^2 (absolute, PQ-decoded)"},
                    {"primaries", "Rec.2020"},
                    {"view", view},
                    {"source", in.source}};
    capture::writeExrHalf(dir / (in.name + "-nits.exr"), in.width, in.height, 3, nits.data(), meta);
    json j = {{"view", view},
              {"peak_nits", peak},
              {"at_peak", n ? static_cast<double>(atPeak) / static_cast<double>(n) : 0.0},
              {"png", "hdr/" + in.name + "-pq.png"},
              {"exr", "hdr/" + in.name + "-nits.exr"}};
    if (chart) {
        const size_t ev0 =
            static_cast<size_t>(std::find(chart->evs.begin(), chart->evs.end(), 0.0f) - chart->evs.begin());
        const size_t grey = chart->sweepPixel(chart->hues.size(), ev0); // the grey ramp at EV 0
        j["mid_grey_nits"] = nits[3 * grey + 1];
    }
    return j;
}

/// The transform named by `part` (case-insensitive substring of its label; an exact label wins).
size_t findTransform(const std::vector<Transform>& ts, const std::string& part) {
    std::vector<size_t> hits;
    for (size_t i = 0; i < ts.size(); ++i) {
        if (lower(ts[i].label) == lower(part))
            return i;
        if (lower(ts[i].label).find(lower(part)) != std::string::npos)
            hits.push_back(i);
    }
    if (hits.size() == 1)
        return hits[0];
    std::string list;
    for (const Transform& t : ts)
        list += "\n  " + t.label;
    throw std::runtime_error("--pair: '" + part + "' names " + (hits.empty() ? "no" : "more than one") +
                             " transform; the transforms are:" + list);
}

std::string shortLabel(const Transform& t) {
    return t.tonemapperId.empty() ? t.config + ": " + t.view : tm::tonemapper(t.tonemapperId).name;
}

/// sheets/<input>-bracket.png: one row per transform, the source at -4..+4 EV.
void bracketSheet(const fs::path& file, const Input& in, const std::vector<Transform>& ts,
                  const tm::TextRenderer& label) {
    constexpr int TW = 120, LABEL_W = 330, GAP = 4;
    int th = 0;
    const std::vector<float> small = tm::downscaleBox(in.rgb, in.width, in.height, TW, th);
    const int head = label.lineHeight() + 8;
    tm::Canvas c(LABEL_W + 9 * (TW + GAP) + GAP, head + static_cast<int>(ts.size()) * (th + GAP) + GAP,
                 0.12f);
    for (int e = 0; e < 9; ++e)
        label.draw(c.rgb, c.width, c.height, LABEL_W + GAP + e * (TW + GAP) + 4, 4 + label.ascender(),
                   (e < 4    ? ""
                    : e == 4 ? " "
                             : "+") +
                       std::to_string(e - 4) + " EV",
                   {1, 1, 1});
    for (size_t ti = 0; ti < ts.size(); ++ti) {
        const int y = head + static_cast<int>(ti) * (th + GAP);
        std::string text = shortLabel(ts[ti]);
        while (text.size() > 4 && label.width(text) > LABEL_W - 8)
            text = text.substr(0, text.size() - 4) + "...";
        label.draw(c.rgb, c.width, c.height, 4, y + th / 2 + label.ascender() / 2, text, {1, 1, 1});
        for (int e = 0; e < 9; ++e) {
            std::vector<float> exposed = small;
            for (float& v : exposed)
                v *= std::exp2(static_cast<float>(e - 4));
            const std::vector<float> code = applyTransform(ts[ti], exposed);
            c.blit(code.data(), TW, th, LABEL_W + GAP + e * (TW + GAP), y);
        }
    }
    capture::writePng8(file, c.width, c.height, 3, c.rgb.data());
}

/// sheets/<input>-falsecolour.png: the source's luminance in stops over 0.18, with the legend.
void falseColourSheet(const fs::path& file, const Input& in, const tm::TextRenderer& label) {
    const int w = std::min(720, in.width);
    int h = 0;
    const std::vector<float> small = tm::downscaleBox(in.rgb, in.width, in.height, w, h);
    const std::vector<float> fc = tm::falseColourStops(small.data(), small.size() / 3);
    const int legend = 2 * label.lineHeight() + 12;
    constexpr int CELL = 76; // legend cell: swatch + label
    const int cw = std::max(w, static_cast<int>(tm::FALSE_COLOUR_BANDS.size()) * CELL);
    tm::Canvas c(cw, h + legend, 0.12f);
    c.blit(fc.data(), w, h, 0, 0);
    label.draw(c.rgb, c.width, c.height, 4, h + 4 + label.ascender(),
               "scene-linear luminance, stops over 0.18 (source, before any transform)", {1, 1, 1});
    for (size_t i = 0; i < tm::FALSE_COLOUR_BANDS.size(); ++i) {
        const auto& b = tm::FALSE_COLOUR_BANDS[i];
        const int x = static_cast<int>(i) * CELL, y = h + label.lineHeight() + 8;
        c.fillRect(x + 2, y, 14, label.lineHeight(), b.colour);
        label.draw(c.rgb, c.width, c.height, x + 18, y + label.ascender(), b.label, {0.85f, 0.85f, 0.85f});
    }
    capture::writePng8(file, c.width, c.height, 3, c.rgb.data());
}

/// sheets/<input>-histograms.png: per transform, R, G, B histograms of its code values (log counts).
void histogramSheet(const fs::path& file, const std::vector<tm::Histogram>& hs,
                    const std::vector<Transform>& ts, const tm::TextRenderer& label) {
    constexpr int PW = 300, PH = 90, COLS = 3, GAP = 8;
    const int cellH = label.lineHeight() + 4 + PH + GAP;
    const int rows = (static_cast<int>(ts.size()) + COLS - 1) / COLS;
    tm::Canvas c(COLS * (PW + GAP) + GAP, rows * cellH + GAP, 0.12f);
    for (size_t i = 0; i < ts.size(); ++i) {
        const int x = GAP + static_cast<int>(i) % COLS * (PW + GAP),
                  y = GAP + static_cast<int>(i) / COLS * cellH;
        std::string text = shortLabel(ts[i]);
        while (text.size() > 4 && label.width(text) > PW)
            text = text.substr(0, text.size() - 4) + "...";
        label.draw(c.rgb, c.width, c.height, x, y + label.ascender(), text, {1, 1, 1});
        tm::plotHistogram(c, x, y + label.lineHeight() + 4, PW, PH, hs[i]);
    }
    capture::writePng8(file, c.width, c.height, 3, c.rgb.data());
}

/// sheets/<input>-wipe.png: A | B wipe, and |A - B| x 4 below; returns the largest |A - B|.
float wipeSheet(const fs::path& file, const Input& in, const std::vector<float>& a,
                const std::vector<float>& b, const Transform& ta, const Transform& tb,
                const tm::TextRenderer& label) {
    const int w = std::min(720, in.width);
    int h = 0;
    const std::vector<float> sa = tm::downscaleBox(a, in.width, in.height, w, h);
    const std::vector<float> sb = tm::downscaleBox(b, in.width, in.height, w, h);
    float maxDiff = 0.0f;
    tm::difference(a.data(), b.data(), a.size() / 3, 4.0f, maxDiff); // full-resolution maximum
    float unused = 0.0f;
    const std::vector<float> diff = tm::difference(sa.data(), sb.data(), sa.size() / 3, 4.0f, unused);
    const std::vector<float> wiped = tm::wipe(sa.data(), sb.data(), w, h);
    const int lh = label.lineHeight() + 6;
    tm::Canvas c(std::max(w, 600), 2 * (h + lh), 0.12f);
    label.draw(c.rgb, c.width, c.height, 4, 3 + label.ascender(),
               "left: " + shortLabel(ta) + "   right: " + shortLabel(tb), {1, 1, 1});
    c.blit(wiped.data(), w, h, 0, lh);
    char text[96];
    std::snprintf(text, sizeof text, "|left - right| x 4 (largest difference %.3f in code values)",
                  static_cast<double>(maxDiff));
    label.draw(c.rgb, c.width, c.height, 4, h + lh + 3 + label.ascender(), text, {1, 1, 1});
    c.blit(diff.data(), w, h, 0, h + 2 * lh);
    capture::writePng8(file, c.width, c.height, 3, c.rgb.data());
    return maxDiff;
}

/// Each shipped tonemapper's LUT (through OCIO's CPU processor) against its closed form, over the chart and
/// every input, for several 3D LUT sizes where it has one; and what each costs per megapixel (steady_clock,
/// median of 3, one thread).
json lutAccuracyAndCost(const fs::path& out, const std::vector<Input>& inputs) {
    std::vector<float> pool;
    for (const Input& in : inputs) // up to ~1 Mpixel of every input, strided
        for (size_t i = 0, step = std::max<size_t>(1, in.rgb.size() / 3 / (1u << 20) * inputs.size());
             i < in.rgb.size() / 3; i += step)
            pool.insert(pool.end(), &in.rgb[3 * i], &in.rgb[3 * i] + 3);
    const size_t n = pool.size() / 3;
    auto timeIt = [&](const auto& fn) {
        std::vector<double> ms;
        for (int r = 0; r < 3; ++r) {
            const auto t0 = std::chrono::steady_clock::now();
            fn();
            ms.push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        }
        std::sort(ms.begin(), ms.end());
        return ms[1] / (static_cast<double>(n) / 1e6);
    };
    json rows = json::array();
    for (const tm::Tonemapper& t : tm::tonemappers()) {
        std::vector<float> closed(pool.size());
        const double closedMs = timeIt([&] {
            for (size_t i = 0; i < n; ++i) {
                const tm::Rgb d = t.apply({pool[3 * i], pool[3 * i + 1], pool[3 * i + 2]});
                for (size_t k = 0; k < 3; ++k)
                    closed[3 * i + k] = tm::srgbEncode(d[k]);
            }
        });
        const std::vector<int> sizes =
            t.id == "pbr-neutral" ? std::vector<int>{17, 33, 65} : std::vector<int>{0};
        for (int size : sizes) {
            const fs::path dir = out / "ocio-lut-sizes" / (t.id + "-" + std::to_string(size));
            const tm::GeneratedConfig g = tm::writeTonemapConfig(dir, size == 0 ? 2 : size);
            ColorPipeline p = ColorPipeline::fromFile(g.path);
            p.select(g.display, g.views.at(t.id));
            std::vector<float> rgba = toRgba(pool);
            const double lutMs = timeIt([&] {
                rgba = toRgba(pool);
                p.applyCpu(rgba.data(), n);
            });
            std::vector<float> err;
            err.reserve(n);
            for (size_t i = 0; i < n; ++i) {
                float e = 0.0f;
                for (size_t k = 0; k < 3; ++k)
                    e = std::max(e, std::fabs(rgba[4 * i + k] - closed[3 * i + k]));
                err.push_back(e);
            }
            std::sort(err.begin(), err.end());
            rows.push_back(
                {{"tonemapper", t.id},
                 {"name", t.name},
                 {"lut", size == 0
                             ? (t.perChannel ? "1D half-domain (65536)" : "AgX: matrices + 1D half-domain")
                             : "3D " + std::to_string(size) + "^3, log2 shaper"},
                 {"max_code_error", err.back()},
                 {"p99_code_error", err[static_cast<size_t>(0.99 * static_cast<double>(err.size() - 1))]},
                 {"lut_ms_per_mpixel", lutMs},
                 {"closed_form_ms_per_mpixel", closedMs},
                 {"pixels", n}});
        }
    }
    fs::remove_all(out / "ocio-lut-sizes");
    return rows;
}

/// The ranking over every scene-linear input: mean clipped fraction and mean hue shift per transform, among
/// the sRGB displays only ("clipped", a code at the display maximum, means nothing comparable on a PQ
/// display whose maximum is 10000 cd/m^2).
struct Ranking {
    std::string leastClip, leastHue;
    double bestClip = 2.0, bestHue = 1e9;
};

Ranking rank(const json& report) {
    std::set<std::string> srgbLabels;
    for (const json& t : report["transforms"])
        if (lower(t["display"].get<std::string>()).find("srgb") != std::string::npos)
            srgbLabels.insert(t["label"].get<std::string>());
    std::map<std::string, std::pair<double, double>> sums;
    std::map<std::string, int> counts;
    for (const json& in : report["inputs"]) {
        if (in["ldr"].get<bool>())
            continue;
        for (const json& r : in["results"]) {
            if (!srgbLabels.count(r["transform"].get<std::string>()))
                continue;
            auto& s = sums[r["transform"].get<std::string>()];
            s.first += r["metrics"]["clipped"].get<double>();
            s.second += r["metrics"]["hue_shift_mean_deg"].get<double>();
            ++counts[r["transform"].get<std::string>()];
        }
    }
    Ranking k;
    for (const auto& [name, s] : sums) {
        const double c = s.first / counts[name], h = s.second / counts[name];
        if (c < k.bestClip)
            k.bestClip = c, k.leastClip = name;
        if (h < k.bestHue)
            k.bestHue = h, k.leastHue = name;
    }
    return k;
}

/// One input's table of transforms (the test chart adds its sweep's columns).
void inputTable(std::ostringstream& md, const json& in) {
    md << "| transform | clipped % | crushed % | hue shift mean / p95 (deg) | chroma ratio | contrast "
          "kept | "
          "neutral drift | GPU - CPU max |"
       << (in["name"] == "test-chart" ? " lum. reversals | hue flips | 0.18 -> code |" : "")
       << "\n|---|---|---|---|---|---|---|---|" << (in["name"] == "test-chart" ? "---|---|---|" : "") << "\n";
    for (const json& r : in["results"]) {
        const json& m = r["metrics"];
        md << "| " << r["transform"].get<std::string>() << " | " << fmt(100 * m["clipped"].get<double>(), 2)
           << " | " << fmt(100 * m["crushed"].get<double>(), 2) << " | "
           << fmt(m["hue_shift_mean_deg"].get<double>(), 2) << " / "
           << fmt(m["hue_shift_p95_deg"].get<double>(), 2) << " | " << fmt(m["chroma_ratio"].get<double>())
           << " | " << fmt(m["contrast_kept"].get<double>()) << " | "
           << fmt(m["neutral_drift"].get<double>(), 4) << " | ";
        if (r.contains("gpu_cpu_max_difference")) {
            char b[32];
            std::snprintf(b, sizeof b, "%.1e", r["gpu_cpu_max_difference"].get<double>());
            md << b;
        } else {
            md << "n/a";
        }
        md << " |";
        if (r.contains("sweep"))
            md << " " << r["sweep"]["luminance_reversals"].get<int>() << " | "
               << r["sweep"]["hue_flips"].get<int>() << " | "
               << fmt(r["sweep"]["mid_grey_code"].get<double>()) << " |";
        md << "\n";
    }
}

/// One input's section: its census, its table, its sheets and its HDR output.
void inputSection(std::ostringstream& md, const json& in) {
    const json& c = in["census"];
    md << "## " << in["name"].get<std::string>() << "\n\n"
       << in["source"].get<std::string>() << ", " << in["width"].get<int>() << "x" << in["height"].get<int>()
       << ", NaN " << c["nan"].get<size_t>() << ", Inf " << c["inf"].get<size_t>() << ", negative "
       << c["negative"].get<size_t>() << "\n\n";
    inputTable(md, in);
    const std::string name = in["name"].get<std::string>();
    md << "\n![" << name << "](sheets/" << name << ".png)\n\n";
    const json& hj = in["hdr"];
    md << "HDR display (Rec.2100 PQ, " << hj["view"].get<std::string>() << "): peak "
       << fmt(hj["peak_nits"].get<double>(), 1) << " cd/m^2, " << fmt(100 * hj["at_peak"].get<double>(), 2)
       << "% of pixels at the 1000 cd/m^2 peak"
       << (hj.contains("mid_grey_nits")
               ? ", 0.18 grey -> " + fmt(hj["mid_grey_nits"].get<double>(), 1) + " cd/m^2"
               : std::string())
       << "; " << hj["png"].get<std::string>() << " (16-bit PQ codes), " << hj["exr"].get<std::string>()
       << " (cd/m^2).\n\n";
    md << "Exposure bracket, -4..+4 EV, per transform:\n\n![" << name << " bracket](sheets/" << name
       << "-bracket.png)\n\n";
    md << "False colour of the source in stops:\n\n![" << name << " false colour](sheets/" << name
       << "-falsecolour.png)\n\n";
    md << "Histograms of the code values (R, G, B; log counts):\n\n![" << name << " histograms](sheets/"
       << name << "-histograms.png)\n\n";
    md << "Wipe and difference: " << in["pair"]["a"].get<std::string>() << " | "
       << in["pair"]["b"].get<std::string>() << " (largest difference "
       << fmt(in["pair"]["max_code_difference"].get<double>()) << "):\n\n![" << name << " wipe](sheets/"
       << name << "-wipe.png)\n\n";
}

/// The shipped LUTs against their closed forms, and the displays left out.
void lutSection(std::ostringstream& md, const json& report) {
    md << "## Shipped LUTs against their closed forms\n\nsRGB code-value error of the generated OCIO config "
          "(OCIO CPU processor) against the CPU closed form, over the chart and up to ~1 Mpixel of the "
          "inputs; "
          "cost per megapixel on one core (steady_clock, median of 3).\n\n"
          "| tonemapper | LUT | max error | p99 error | OCIO LUT ms/Mpx | closed form ms/Mpx "
          "|\n|---|---|---|---|---|---|\n";
    for (const json& r : report["luts"]) {
        char b[64];
        md << "| " << r["name"].get<std::string>() << " | " << r["lut"].get<std::string>() << " | ";
        std::snprintf(b, sizeof b, "%.2e | %.2e", r["max_code_error"].get<double>(),
                      r["p99_code_error"].get<double>());
        md << b << " | " << fmt(r["lut_ms_per_mpixel"].get<double>(), 1) << " | "
           << fmt(r["closed_form_ms_per_mpixel"].get<double>(), 1) << " |\n";
    }
    if (!report["skipped_displays"].empty()) {
        md << "\nDisplays not compared: ";
        for (const json& s : report["skipped_displays"])
            md << s.get<std::string>() << "; ";
        md << "\n";
    }
}

std::string markdownReport(const json& report, const Ranking& k) {
    std::ostringstream md;
    md << "# Tonemapping comparison\n\nGenerated by `pacifica tonemap compare`. Metrics: docs/TONEMAP.md. "
          "GPU path: "
       << (report["gl_renderer"].get<std::string>().empty()
               ? std::string("not run")
               : "GL_RENDERER " + report["gl_renderer"].get<std::string>())
       << ".\n\n"
       << "Over the scene-linear inputs, among the sRGB-display transforms: **least clipping**: "
       << k.leastClip << " (mean " << fmt(100 * k.bestClip, 2)
       << "% of pixels); **least hue shift**: " << k.leastHue << " (mean " << fmt(k.bestHue, 2)
       << " deg).\n\n";
    for (const json& in : report["inputs"])
        inputSection(md, in);
    lutSection(md, report);
    return md.str();
}

std::string escapeHtml(const std::string& s) {
    std::string o;
    for (char c : s)
        o += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
    return o;
}

/// The markdown report as one self-contained HTML file: the same tables, the sheets embedded as data URIs.
std::string htmlReport(const std::string& markdown, const fs::path& out) {
    std::string body;
    std::istringstream lines(markdown);
    bool inTable = false;
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("|", 0) == 0) {
            if (line.rfind("|---", 0) == 0)
                continue;
            if (!inTable)
                body += "<table>\n";
            std::string row = "<tr>";
            std::istringstream cells(line.substr(1));
            for (std::string cell; std::getline(cells, cell, '|');)
                row += (inTable ? "<td>" : "<th>") + escapeHtml(cell) + (inTable ? "</td>" : "</th>");
            body += row + "</tr>\n";
            inTable = true;
            continue;
        }
        if (inTable)
            body += "</table>\n";
        inTable = false;
        if (line.rfind("# ", 0) == 0)
            body += "<h1>" + escapeHtml(line.substr(2)) + "</h1>\n";
        else if (line.rfind("## ", 0) == 0)
            body += "<h2>" + escapeHtml(line.substr(3)) + "</h2>\n";
        else if (line.rfind("![", 0) == 0) {
            const size_t a = line.find("](") + 2;
            const std::string file = line.substr(a, line.size() - a - 1);
            std::ifstream in(out / file, std::ios::binary);
            const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
            body += "<img alt=\"" + escapeHtml(file) + "\" src=\"data:image/png;base64," + base64(bytes) +
                    "\">\n";
        } else if (!line.empty())
            body += "<p>" + escapeHtml(line) + "</p>\n";
    }
    if (inTable)
        body += "</table>\n";
    return "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>Tonemapping comparison</title>\n"
           "<style>body{font-family:sans-serif;background:#1e1e1e;color:#ddd;margin:2em}"
           "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #555;padding:2px 8px;"
           "text-align:right}td:first-child,th:first-child{text-align:left}img{max-width:100%}</style>"
           "</head><body>\n" +
           body + "</body></html>\n";
}

void writeReports(const fs::path& out, const json& report) {
    writeFileAtomically(out / "metrics.json", reportText(report));
    const Ranking k = rank(report);
    const std::string md = markdownReport(report, k);
    writeFileAtomically(out / "report.md", md);
    writeFileAtomically(out / "report.html", htmlReport(md, out));
    std::fprintf(stderr, "pacifica: least clipping: %s (%.2f%%); least hue shift: %s (%.2f deg)\n",
                 k.leastClip.c_str(), 100 * k.bestClip, k.leastHue.c_str(), k.bestHue);
}

void checkCompareOptions(const TonemapCompareOptions& o) {
    if (o.inputs.empty())
        throw std::runtime_error(
            "tonemap compare: give at least one input (EXR, replay folder or flight file)");
    if (o.outDir.empty())
        throw std::runtime_error("tonemap compare: --out DIR is required");
    if (o.lut3dSize < 2 || o.lut3dSize > 129)
        throw std::runtime_error("--lut3d " + std::to_string(o.lut3dSize) + " is outside 2..129");
    if (o.tileWidth < 64 || o.tileWidth > 4096)
        throw std::runtime_error("--tile-width " + std::to_string(o.tileWidth) + " is outside 64..4096");
}

Input chartInput(const tm::Chart& chart) {
    Input c;
    c.name = "test-chart";
    c.source = "generated hue x exposure chart (tonemap/Metrics.h)";
    c.width = chart.width;
    c.height = chart.height;
    c.rgb = chart.rgb;
    c.census = tm::census(c.rgb.data(), c.rgb.size() / 3);
    c.chart = true;
    return c;
}

/// The images one argument stands for, with their names: a replay folder's frames, a flight file rendered
/// into out/renders, or an image.
std::vector<std::pair<fs::path, std::string>> argumentImages(const std::string& arg, const fs::path& out,
                                                             int framesPerFolder) {
    const fs::path p(arg);
    if (!fs::exists(p))
        throw std::runtime_error(arg + ": no such file or folder");
    std::vector<std::pair<fs::path, std::string>> files;
    if (fs::is_directory(p)) {
        if (!fs::exists(p / "summary.json"))
            throw std::runtime_error(arg + ": a folder that is not a replay output (no summary.json)");
        for (const fs::path& f : replayFrames(p, framesPerFolder))
            files.emplace_back(f, p.filename().string() + "-" + f.stem().string());
        return files;
    }
    std::string format;
    try {
        format = recording::detectFormat(p);
    } catch (const std::exception&) {
    }
    if (format.empty()) {
        files.emplace_back(p, p.stem().string());
        return files;
    }
    const fs::path renderDir = out / "renders" / fileSlug(p.stem().string());
    for (const fs::path& f : renderFlight(p, renderDir, framesPerFolder))
        files.emplace_back(f, fileSlug(p.stem().string()) + "-" + f.stem().string());
    return files;
}

/// The inputs, all read before any work: the chart first, then every argument's images. A render is named
/// where it will be, not in the staging directory `out`.
std::vector<Input> collectInputs(const TonemapCompareOptions& o, const fs::path& out,
                                 const tm::Chart& chart) {
    std::vector<Input> inputs;
    inputs.push_back(chartInput(chart));
    const std::string staged = out.string() + "/";
    for (const std::string& arg : o.inputs)
        for (const auto& [file, name] : argumentImages(arg, out, o.framesPerFolder)) {
            inputs.push_back(fromImage(file, fileSlug(name), o.maxPixels));
            if (inputs.back().source.rfind(staged, 0) == 0)
                inputs.back().source = (o.outDir / inputs.back().source.substr(staged.size())).string();
        }
    return inputs;
}

/// The transforms: the shipped tonemappers (the generated config), then the sRGB views of the embedded
/// config, $OCIO's and every --ocio-config's; the displays left out in `skipped`.
std::vector<Transform> collectTransforms(const TonemapCompareOptions& o, const tm::GeneratedConfig& generated,
                                         std::vector<std::string>& skipped) {
    std::vector<Transform> transforms;
    const ColorPipeline shipped = ColorPipeline::fromFile(generated.path);
    for (const tm::Tonemapper& t : tm::tonemappers()) {
        Transform tr{"pacifica: " + t.name,    "pacifica", generated.display,
                     generated.views.at(t.id), t.id,       shipped};
        tr.pipeline.select(tr.display, tr.view);
        transforms.push_back(std::move(tr));
    }
    addConfigViews(ColorPipeline::createDefault(), "embedded", transforms, skipped);
    std::vector<fs::path> configs;
    if (const char* env = std::getenv("OCIO"); env && *env)
        configs.emplace_back(env);
    configs.insert(configs.end(), o.ocioConfigs.begin(), o.ocioConfigs.end());
    for (const fs::path& c : configs) {
        ColorPipeline p = ColorPipeline::fromFile(c); // throws naming the file
        // The inputs are linear Rec.709; a config whose scene_linear is another space (ACEScg in the ACES
        // configs) is entered through its linear Rec.709 colour space.
        const std::string rec709 = p.linearRec709ColorSpace();
        if (!rec709.empty())
            p.setInput(rec709);
        else
            std::fprintf(stderr,
                         "pacifica: warning: %s has no linear Rec.709 colour space; its views start from "
                         "scene_linear\n",
                         c.c_str());
        addConfigViews(p, p.configDescription(), transforms, skipped);
    }
    return transforms;
}

json transformsJson(const std::vector<Transform>& transforms) {
    json j = json::array();
    for (const Transform& t : transforms)
        j.push_back({{"label", t.label},
                     {"decoded_by", t.decodesToXyz ? "display colour space -> CIE XYZ" : "sRGB EOTF"},
                     {"config", t.config},
                     {"display", t.display},
                     {"view", t.view},
                     {"closed_form", t.tonemapperId}});
    return j;
}

/// One input's contact sheet: a header (name, size, census), then a labelled tile per transform, three
/// columns wide.
class ContactSheet {
public:
    ContactSheet(const Input& in, int tileWidth, size_t transforms, const tm::TextRenderer& label)
        : mLabel(label), mTw(std::min(tileWidth, std::max(in.width, 64))),
          mTh(std::max(1, static_cast<int>(std::lround(static_cast<double>(in.height) * mTw / in.width)))),
          mLabelH(2 * label.lineHeight() + 6), mHeaderH(2 * label.lineHeight() + 10) {
        const int rows = (static_cast<int>(transforms) + COLUMNS - 1) / COLUMNS;
        mW = COLUMNS * mTw + (COLUMNS + 1) * 8;
        mH = mHeaderH + rows * (mTh + mLabelH + 8) + 8;
        mSheet.assign(static_cast<size_t>(mW) * static_cast<size_t>(mH) * 3, 0.12f);
        label.draw(mSheet, mW, mH, 8, 6 + label.ascender(),
                   in.name + "  (" + std::to_string(in.width) + "x" + std::to_string(in.height) + ", max " +
                       fmt(in.census.maxValue, 1) + ")",
                   {1, 1, 1});
        label.draw(mSheet, mW, mH, 8, 8 + label.lineHeight() + label.ascender(),
                   "NaN " + std::to_string(in.census.nan) + ", Inf " + std::to_string(in.census.inf) +
                       ", negative " + std::to_string(in.census.negative) +
                       (in.ldr ? "   LDR input: not scene-linear" : ""),
                   {0.75f, 0.75f, 0.75f});
    }
    /// Transform ti's tile: its config and display / view (or tonemapper) above the downscaled codes.
    void tile(size_t ti, const Transform& t, const std::vector<float>& code, const Input& in) {
        int tileH = 0;
        const std::vector<float> tile = tm::downscaleBox(code, in.width, in.height, mTw, tileH);
        const int col = static_cast<int>(ti) % COLUMNS, row = static_cast<int>(ti) / COLUMNS;
        const int x0 = 8 + col * (mTw + 8), y0 = mHeaderH + row * (mTh + mLabelH + 8);
        auto fit = [&](std::string text) {
            while (text.size() > 4 && mLabel.width(text) > mTw)
                text = text.substr(0, text.size() - 4) + "...";
            return text;
        };
        const std::string line2 =
            t.tonemapperId.empty() ? t.display + " / " + t.view : tm::tonemapper(t.tonemapperId).name;
        mLabel.draw(mSheet, mW, mH, x0, y0 + mLabel.ascender() + 2, fit(t.config), {0.7f, 0.7f, 0.7f});
        mLabel.draw(mSheet, mW, mH, x0, y0 + mLabel.lineHeight() + mLabel.ascender() + 2, fit(line2),
                    {1, 1, 1});
        for (int y = 0; y < std::min(mTh, tileH); ++y)
            std::copy_n(&tile[static_cast<size_t>(y) * static_cast<size_t>(mTw) * 3],
                        static_cast<size_t>(mTw) * 3,
                        &mSheet[(static_cast<size_t>(y0 + mLabelH + y) * static_cast<size_t>(mW) +
                                 static_cast<size_t>(x0)) *
                                3]);
    }
    void write(const fs::path& file) const { capture::writePng8(file, mW, mH, 3, mSheet.data()); }

private:
    static constexpr int COLUMNS = 3;
    const tm::TextRenderer& mLabel;
    int mTw, mTh, mLabelH, mHeaderH, mW = 0, mH = 0;
    std::vector<float> mSheet;
};

/// What every input is compared with.
struct Comparison {
    const TonemapCompareOptions& o;
    const fs::path& out;
    const tm::TextRenderer& label;
    const tm::Chart& chart;
    const std::vector<Transform>& transforms;
    size_t pairA, pairB; // the wipe's two transforms
    GpuCheck& gpu;
    const ColorPipeline& hdr;
    std::string hdrView;

    json result(const Input& in, size_t ti, const std::vector<float>& code) const;
    json input(const Input& in) const;
};

/// Transform ti on input `in`: its metrics, the GPU path's largest difference from the CPU's codes, and on
/// the chart the sweep's.
json Comparison::result(const Input& in, size_t ti, const std::vector<float>& code) const {
    const Transform& t = transforms[ti];
    const std::vector<float> linear = displayLinear(t, code);
    const tm::TransformMetrics m = tm::measure(in.rgb.data(), code.data(), linear.data(), in.rgb.size() / 3);
    json jr = {{"transform", t.label}, {"metrics", metricsJson(m)}};
    if (o.gpu && gpu.available()) {
        // Uploaded and read back in the same row order, pixel for pixel (the pass texelFetch-es).
        const std::vector<float> g = gpu.run(ti, t, in.rgb, in.width, in.height);
        double worst = 0.0;
        for (size_t i = 0; i < g.size(); ++i)
            if (std::isfinite(code[i]) && std::isfinite(g[i]))
                worst = std::max(worst, static_cast<double>(std::fabs(g[i] - code[i])));
            else if (std::isfinite(code[i]) != std::isfinite(g[i]))
                worst = INFINITY;
        jr["gpu_cpu_max_difference"] = worst;
    }
    if (in.chart) {
        const tm::SweepMetrics s = tm::sweepMetrics(chart, code.data(), linear.data());
        jr["sweep"] = {{"luminance_reversals", s.luminanceReversals},
                       {"hue_flips", s.hueFlips},
                       {"mid_grey_code", s.whereMidGreyLands}};
    }
    return jr;
}

/// One input through every transform: its entry in metrics.json and its sheets (contact, HDR, bracket,
/// false colour, histograms, wipe).
json Comparison::input(const Input& in) const {
    json ji = {{"name", in.name},
               {"source", in.source},
               {"width", in.width},
               {"height", in.height},
               {"ldr", in.ldr},
               {"census",
                {{"pixels", in.census.pixels},
                 {"nan", in.census.nan},
                 {"inf", in.census.inf},
                 {"negative", in.census.negative},
                 {"max", in.census.maxValue}}},
               {"results", json::array()}};
    ContactSheet sheet(in, o.tileWidth, transforms.size(), label);
    std::vector<tm::Histogram> histograms;
    std::vector<float> codeA, codeB;
    for (size_t ti = 0; ti < transforms.size(); ++ti) {
        const std::vector<float> code = applyTransform(transforms[ti], in.rgb);
        histograms.push_back(tm::histogram(code.data(), code.size() / 3, 64));
        if (ti == pairA)
            codeA = code;
        if (ti == pairB)
            codeB = code;
        ji["results"].push_back(result(in, ti, code));
        sheet.tile(ti, transforms[ti], code, in);
    }
    const fs::path sheets = out / "sheets";
    sheet.write(sheets / (in.name + ".png"));
    ji["hdr"] = hdrOutput(out / "hdr", in, hdr, hdrView, in.chart ? &chart : nullptr);
    bracketSheet(sheets / (in.name + "-bracket.png"), in, transforms, label);
    falseColourSheet(sheets / (in.name + "-falsecolour.png"), in, label);
    histogramSheet(sheets / (in.name + "-histograms.png"), histograms, transforms, label);
    ji["pair"] = {{"a", transforms[pairA].label},
                  {"b", transforms[pairB].label},
                  {"max_code_difference", wipeSheet(sheets / (in.name + "-wipe.png"), in, codeA, codeB,
                                                    transforms[pairA], transforms[pairB], label)}};
    return ji;
}

} // namespace

/// Options, inputs and transforms are checked before any work; everything is written into a staging
/// directory moved into place at the end.
void runTonemapCompare(const TonemapCompareOptions& o) {
    checkCompareOptions(o);
    Staging staging(o.outDir);
    const fs::path out = staging.dir();
    const tm::TextRenderer label(tm::defaultFontPath(), 14);
    const tm::Chart chart = tm::testChart(16);
    const std::vector<Input> inputs = collectInputs(o, out, chart);
    std::vector<std::string> skipped;
    const tm::GeneratedConfig generated = tm::writeTonemapConfig(out / "ocio", o.lut3dSize);
    const std::vector<Transform> transforms = collectTransforms(o, generated, skipped);
    const size_t comma = o.pair.find(',');
    if (comma == std::string::npos)
        throw std::runtime_error("--pair '" + o.pair + "': expected two transforms, A,B");
    const size_t pairA = findTransform(transforms, o.pair.substr(0, comma));
    const size_t pairB = findTransform(transforms, o.pair.substr(comma + 1));
    std::fprintf(stderr, "pacifica: %zu inputs x %zu transforms\n", inputs.size(), transforms.size());
    GpuCheck gpu(transforms.size(), o.gpu);
    ColorPipeline hdr = ColorPipeline::fromFile(generated.path);
    hdr.select(generated.hdrDisplay, generated.hdrView);
    fs::create_directories(out / "hdr");

    json report;
    report["transforms"] = transformsJson(transforms);
    report["skipped_displays"] = skipped;
    report["gl_renderer"] = gpu.available() ? gpu.renderer() : "";
    report["inputs"] = json::array();
    fs::create_directories(out / "sheets");
    const Comparison comparison{o, out, label, chart, transforms, pairA, pairB, gpu, hdr, generated.hdrView};
    for (const Input& in : inputs)
        report["inputs"].push_back(comparison.input(in));
    report["luts"] = lutAccuracyAndCost(out, inputs);
    writeReports(out, report);
    staging.commit();
    std::fprintf(stderr, "pacifica: wrote %s (report.html, report.md, metrics.json, sheets/)\n",
                 o.outDir.c_str());
}

} // namespace pacifica::tools
