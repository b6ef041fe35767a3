// libFuzzer target: the IGC parser and the attitude it derives from the track (engine/recording/src/Igc.cpp).
#include <recording/Recording.h>

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        const pacifica::recording::Recording r = pacifica::recording::parseIgc(
            std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.igc");
        (void)r.objects.at(0).sampleAt(r.endTime);
    } catch (const pacifica::recording::RecordingError&) {
    }
    return 0;
}
