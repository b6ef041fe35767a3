// Replay: renders a recorded flight path into deterministic headless frames — scene-linear half EXR +
// tonemapped 8-bit PNG per frame, and DIR/summary.json listing every frame (time, pose, files, EXR pixel
// hash) with GL_RENDERER and timings. Used by `pacifica replay` and `./pacifica demo`.
#pragma once

#include "Usage.h"
#include "engine/capture/Capture.h"
#include "ocean/Ocean.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pacifica::tools {

struct ReplayOptions {
    std::filesystem::path flight;
    std::filesystem::path outDir;
    double fps = 10.0;
    int width = 640;
    int height = 360;
    /// --start/--end: seconds on the flight's clock or UTC timestamps (parseTimeArgument, ReplayInput.h);
    /// default: the flight's (CSV) or the first rig's object's (recording) first and last sample.
    std::optional<std::string> start;
    std::optional<std::string> end;
    /// --rig, repeated: one view each (ReplayInput.h, recording/CameraRig.h); empty = the default view.
    std::vector<std::string> rigs;
    /// --video FILE.mp4|.mov: the first view's tonemapped frames, encoded by ffmpeg (VideoWriter.h).
    std::optional<std::filesystem::path> video;
    double speed = 1.0;           ///< --speed: recording seconds per real second (time-lapse > 1)
    long long maxFrames = 100000; ///< --max-frames: a run with more frames is refused before it starts
    /// --egl-device N: render on EGL device N of eglQueryDevicesEXT's list (gl::ContextDesc::eglDevice);
    /// -1 = the first hardware device, else Mesa's surfaceless platform.
    int eglDevice = -1;
    /// --egl-device auto: the device the environment gives this process -- the first entry of
    /// CUDA_VISIBLE_DEVICES (visibleCudaDevice()), found as --cuda-device finds it -- else eglDevice -1's
    /// choice. What a process under a job scheduler (Slurm's GPU GRES) wants.
    bool eglDeviceAuto = false;
    /// --cuda-device ID: render on that CUDA device (an index in this process's CUDA numbering, which
    /// CUDA_VISIBLE_DEVICES renumbers from 0, or a GPU-UUID), found through EGL_NV_device_cuda
    /// (gl::ContextDesc::cudaDevice); `pacifica farm chunk` passes visibleCudaDevice(). Not with
    /// --egl-device.
    std::string cudaDevice;
    std::string display; ///< empty = the config's default display
    std::string view;    ///< empty = the display's default view
    /// Further views of the same display (--view repeated): the scene is rendered once per frame and
    /// tonemapped once more per extra view, written as frame_NNNNN.<view>.png (slug of the view name).
    std::vector<std::string> extraViews;
    std::optional<std::filesystem::path> ocioConfig;
    /// --exposure EV: pre-exposure (ocean::exposed): every light scaled by 2^EV, so the frame, the EXR and
    /// the OCIO view's input hold radiance x 2^EV (summary.json exposure_ev). A moonlit night wants ~+17.
    double exposureEv = 0.0;
    /// --light spot:SHIP|fixed,key=value...: spot lights on recorded ships or fixed (ReplayLights.h).
    std::vector<std::string> lights;
    bool writeImages = true; ///< false: render, tonemap and read back, but write no images (benchmarks)
    /// --image-compression: zlib level of the EXR (ZIP) and PNG files, both lossless. Fast (level 1, the
    /// default) encodes a 640x360 frame in 35 instead of 80 ms for 1.11x / 1.26x the bytes: on a 2-core
    /// software renderer the encoder's thread takes its core from the render (docs/PERFORMANCE.md).
    capture::Compression imageCompression = capture::Compression::Fast;
    bool progress = true; ///< progress line when stderr is a TTY
    /// --profile: per-pass times in every frame's "pass_ms" and their medians in timings.passes_ms_median
    /// (docs/PERFORMANCE.md): the ocean's passes (OceanRenderer::setPassTiming), objects, tonemap, readback
    /// and image encoding. On llvmpipe it puts a glFinish between passes, which costs a little overlap.
    bool profile = false;
    float fovYDeg = 60.0f;
    ocean::OceanDesc ocean; ///< the ocean to render (surface model, grid, lighting)
    /// --env: HDR lat-long environment (EXR, 3 or 4 channels) for the sky and reflections; it replaces
    /// ocean.lighting.environment and points the sun at the map's brightest region. Read and validated
    /// before anything is written: a missing, unreadable or NaN/Inf/negative file is an error naming it.
    std::optional<std::filesystem::path> environment;
    /// Apply the flight file's events (explosions, ships with their wakes; docs/FLIGHT_FORMAT.md).
    /// false (--no-events): the plain ocean, for comparisons and benchmarks.
    bool events = true;
    /// Draw the recording's aircraft, ships and weapons (ObjectRenderer.h); false: --no-objects.
    bool objects = true;
    /// --frames I-J: render only frames I..J of the run the other options describe, as a chunk of a sharded
    /// run (docs/SCALE.md). Frames 0..I-1 are simulated first without rendering (the pre-roll: the effects'
    /// timeline, the wakes' paths and the ships' sea queries stepped through the same frame times), so frame
    /// k's pixels equal a one-process run's. Each view frame lands on its own (files renamed into DIR, then
    /// its sidecar NAME.check.json with the files' checksums and its summary entry); a frame whose sidecar
    /// has this run's key and matches its files is kept, not rendered again (resume). The chunk's summary is
    /// DIR/chunk-IIIII-JJJJJ.json; summary.json is left alone. Not with --video.
    std::optional<FrameRange> frames;
    /// What a sidecar must name for --frames to keep a frame (set by the CLI): the command line less
    /// --frames,
    /// --cuda-device and --no-progress, as spelled, with the XXH64 of the program's bytes and of every input
    /// file (recording, --env, OCIO config, --height-map), so a frame of a run with other options, another
    /// build or edited inputs is rendered again (the hashes are read only for --frames and the farm's plan,
    /// which use the key). It does not cover the GPU or driver (docs/SCALE.md).
    std::string runKey;
};

/// What a replay run renders with, for benchmarks that time its frames.
struct ReplayRunInfo {
    std::string glRenderer, glVersion, gpuClock, ocioConfig;
    const std::vector<double>* gpuMs = nullptr; ///< the GPU time of every view frame so far (GpuTimer)
};

/// A replay run frame by frame: what runReplay() does, open to benchmarks that time the real frames. The
/// constructor validates everything and builds the run (the output transaction open), renderFrame(k)
/// renders frame k of [0, frameCount()) (the simulation advanced to its time), finish() writes every image
/// and summary.json. A session destroyed unfinished leaves the output directory as it was.
class ReplaySession {
public:
    explicit ReplaySession(const ReplayOptions& options);
    ~ReplaySession();
    ReplaySession(const ReplaySession&) = delete;
    ReplaySession& operator=(const ReplaySession&) = delete;
    long long frameCount() const;
    /// --frames' range (or [0, frameCount() - 1]): runReplay() calls renderFrame for 0..last, and frames
    /// before the first are the pre-roll (simulated, not rendered).
    FrameRange frameRange() const;
    void renderFrame(long long k);
    void finish();
    const ReplayRunInfo& info() const;

private:
    struct State;
    std::unique_ptr<State> mState;
};

/// The GPU a job scheduler gave this process, as --cuda-device names it: "" when CUDA_VISIBLE_DEVICES is
/// unset or empty; its first entry when that is a GPU-UUID; else "0", since CUDA (and NVIDIA's EGL with it)
/// numbers the visible GPUs from 0 (CUDA_VISIBLE_DEVICES=1: the second GPU is CUDA device 0).
std::string visibleCudaDevice();

/// The checks that need nothing but the options (--fps, --fov, --speed, --max-frames, --out or --video,
/// one device, --frames without --video); throws UsageError naming the option. runReplay() starts with them.
void checkReplayOptions(const ReplayOptions& options);

/// The number of frames the run these options describe renders, without rendering: the options checked and
/// the flight read (no GL context, nothing written). Throws as runReplay() does.
long long replayFrameCount(const ReplayOptions& options);

/// Runs the replay. Throws (FlightError, ColorError, ContextError, CaptureError, UsageError) on failure,
/// after removing every file this run wrote, so DIR holds no partial output.
void runReplay(const ReplayOptions& options);

} // namespace pacifica::tools
