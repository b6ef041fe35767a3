// VideoWriter: raw rgb24 frames into `ffmpeg -f rawvideo -i -` (popen), output to a temporary file that
// finish() renames into place.
#include "VideoWriter.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace pacifica::tools {
namespace fs = std::filesystem;

namespace {

std::string shellQuote(const std::string& s) {
    std::string q = "'";
    for (char c : s)
        q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string lowerExt(const fs::path& p) {
    std::string e = p.extension().string();
    std::transform(e.begin(), e.end(), e.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return e;
}

} // namespace

std::string VideoWriter::findFfmpeg(const fs::path& target) {
    const std::string ext = lowerExt(target);
    if (ext != ".mp4" && ext != ".mov")
        throw VideoError("--video " + target.string() +
                         ": expected a .mp4 (H.264) or .mov (ProRes) file name");
    if (const char* env = std::getenv("PACIFICA_FFMPEG")) {
        if (access(env, X_OK) == 0)
            return env;
        throw VideoError("--video: PACIFICA_FFMPEG=" + std::string(env) + " is not an executable file");
    }
    const char* path = std::getenv("PATH");
    std::string p = path ? path : "";
    size_t start = 0;
    while (start <= p.size()) {
        const size_t colon = p.find(':', start);
        const std::string dir =
            p.substr(start, colon == std::string::npos ? std::string::npos : colon - start);
        if (!dir.empty()) {
            const std::string exe = dir + "/ffmpeg";
            if (access(exe.c_str(), X_OK) == 0)
                return exe;
        }
        if (colon == std::string::npos)
            break;
        start = colon + 1;
    }
    throw VideoError("--video: ffmpeg was not found on PATH; install it with `apt-get install ffmpeg` "
                     "(./pacifica deps does) or set PACIFICA_FFMPEG");
}

VideoWriter::VideoWriter(const fs::path& target, int width, int height, double fps, Input input)
    : mTarget(target), mWidth(width), mHeight(height) {
    const std::string ffmpeg = findFfmpeg(target);
    const std::string ext = lowerExt(target);
    fs::path dir = target.parent_path();
    if (dir.empty())
        dir = ".";
    std::error_code ec;
    fs::create_directories(dir, ec); // `--video out/f14.mp4` on a fresh clone
    if (!fs::is_directory(dir, ec))
        throw VideoError("--video " + target.string() + ": cannot create the folder '" + dir.string() + "'");
    mTemp = dir / ("." + target.stem().string() + ".tmp-" + std::to_string(getpid()) + ext);
    char rate[32];
    std::snprintf(rate, sizeof rate, "%.6g", fps);
    const std::string codec = ext == ".mp4" ? "-c:v libx264 -preset medium -crf 18 -pix_fmt yuv420p"
                                            : "-c:v prores_ks -profile:v 3 -pix_fmt yuv422p10le";
    // Odd sizes: H.264 4:2:0 needs even dimensions, so pad by one pixel when needed.
    const std::string pad = ext == ".mp4" ? " -vf " + shellQuote("pad=ceil(iw/2)*2:ceil(ih/2)*2") : "";
    const std::string in = input == Input::Png ? std::string("-f image2pipe -framerate ") + rate + " -c:v png"
                                               : "-f rawvideo -pix_fmt rgb24 -s " + std::to_string(width) +
                                                     "x" + std::to_string(height) + " -r " + rate;
    const std::string cmd = shellQuote(ffmpeg) + " -nostdin -hide_banner -loglevel error -y " + in +
                            " -i - -an" + pad + " " + codec + " " + shellQuote(mTemp.string());
    mPipe = popen(cmd.c_str(), "w");
    if (!mPipe)
        throw VideoError("--video: cannot start ffmpeg (" + ffmpeg + ")");
    if (input == Input::Rgba)
        mRow.resize(static_cast<size_t>(width) * static_cast<size_t>(height) * 3);
}

VideoWriter::~VideoWriter() {
    if (mPipe)
        pclose(mPipe);
    std::error_code ec;
    fs::remove(mTemp, ec); // after a successful finish() it was renamed away: nothing to remove
}

void VideoWriter::addPng(const fs::path& png) {
    std::ifstream in(png, std::ios::binary | std::ios::ate);
    std::string bytes(in ? static_cast<size_t>(in.tellg()) : 0, '\0');
    in.seekg(0);
    if (!in || !in.read(bytes.data(), static_cast<std::streamsize>(bytes.size())))
        throw VideoError("video " + mTarget.string() + ": cannot read the frame " + png.string());
    if (bytes.size() < 8 || bytes.compare(1, 3, "PNG") != 0)
        throw VideoError("video " + mTarget.string() + ": " + png.string() + " is not a PNG file");
    if (std::fwrite(bytes.data(), 1, bytes.size(), mPipe) != bytes.size())
        throw VideoError("video " + mTarget.string() + ": ffmpeg stopped reading frames at " + png.string() +
                         " (see its message above)");
    ++mFrames;
}

void VideoWriter::addFrame(const float* rgba) {
    const size_t n = static_cast<size_t>(mWidth) * static_cast<size_t>(mHeight);
    for (size_t i = 0; i < n; ++i)
        for (size_t c = 0; c < 3; ++c) {
            const float v = rgba[i * 4 + c];
            mRow[i * 3 + c] =
                static_cast<char>(std::lround((std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f)) * 255.0f));
        }
    if (std::fwrite(mRow.data(), 1, mRow.size(), mPipe) != mRow.size())
        throw VideoError("--video: ffmpeg stopped reading frames (see its message above)");
    ++mFrames;
}

void VideoWriter::finish() {
    const int status = pclose(mPipe);
    mPipe = nullptr;
    if (status != 0)
        throw VideoError("--video: ffmpeg failed (exit status " +
                         std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ") writing " +
                         mTarget.string());
    std::error_code ec;
    fs::rename(mTemp, mTarget, ec);
    if (ec)
        throw VideoError("--video: cannot move the video into place at " + mTarget.string() + ": " +
                         ec.message());
}

} // namespace pacifica::tools
