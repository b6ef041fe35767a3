// VideoWriter: encodes the tonemapped frames of a replay into a video by piping raw RGB frames to Debian's
// ffmpeg CLI: `.mp4` as H.264 (libx264, yuv420p, CRF 18), `.mov` as ProRes 422 HQ (prores_ks). The video is
// written to a hidden temporary file beside the target and renamed into place only by finish(), so a failed
// or interrupted run leaves no half-written video (the destructor removes the temporary file).
#pragma once

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace pacifica::tools {

class VideoError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class VideoWriter {
public:
    /// Checks the extension (.mp4 or .mov; else VideoError naming --video) and that ffmpeg can be found
    /// ($PACIFICA_FFMPEG, else `ffmpeg` on $PATH; else VideoError saying how to install it). Nothing is
    /// started.
    static std::string findFfmpeg(const std::filesystem::path& target);

    /// What the frames are: display-encoded RGBA floats (addFrame) or PNG files, decoded by ffmpeg (addPng):
    /// the farm's video, encoded once from the frames its chunks wrote.
    enum class Input { Rgba, Png };

    /// Starts ffmpeg writing width x height frames at fps into a temporary file beside target.
    VideoWriter(const std::filesystem::path& target, int width, int height, double fps,
                Input input = Input::Rgba);
    ~VideoWriter();
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;

    /// One frame of display-encoded RGBA floats, rows top-down (FrameTargets::readDisplay), clamped to 8
    /// bits.
    void addFrame(const float* rgba);
    /// One frame as a PNG file of the video's size (Input::Png), passed to ffmpeg as it is. VideoError naming
    /// the file when it cannot be read.
    void addPng(const std::filesystem::path& png);
    /// Waits for ffmpeg and renames the video into place. VideoError (with ffmpeg's exit status) on failure.
    void finish();
    int frames() const { return mFrames; }

private:
    std::filesystem::path mTarget, mTemp;
    int mWidth, mHeight, mFrames = 0;
    FILE* mPipe = nullptr;
    std::string mRow;
};

} // namespace pacifica::tools
