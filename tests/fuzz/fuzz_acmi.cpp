// libFuzzer target: the streaming Tacview ACMI parser (engine/recording/src/Acmi.cpp). The input is fed in
// chunks whose size comes from the first byte, so line, BOM and continuation boundaries fall anywhere.
// Any input must end in a Recording or a RecordingError: no crash, leak, hang or other exception.
#include <recording/Recording.h>

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0)
        return 0;
    const size_t chunk = 1 + data[0] % 64;
    const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
    try {
        pacifica::recording::AcmiParser parser("fuzz.acmi");
        for (size_t i = 0; i < text.size(); i += chunk)
            parser.feed(text.substr(i, chunk));
        const pacifica::recording::Recording r = parser.finish();
        for (const auto& o : r.objects)
            if (!o.track.empty()) {
                (void)o.sampleAt(0.5 * (o.startTime() + o.endTime()));
                pacifica::recording::RecordedObject derived = o; // what a rig does for 3/5-field tracks
                pacifica::recording::deriveAttitude(derived);
            }
    } catch (const pacifica::recording::RecordingError&) {
    }
    return 0;
}
