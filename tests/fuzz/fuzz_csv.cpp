// libFuzzer target: the project's flight CSV (tools/src/FlightPath.cpp), sampled where it parses.
#include <FlightPath.h>

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        const auto path = pacifica::tools::FlightPath::parse(
            std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.csv");
        (void)path.poseAt(0.5 * (path.startTime() + path.endTime()));
        for (const auto& ship : path.ships())
            (void)ship.headingAt(ship.endTime());
    } catch (const pacifica::tools::FlightError&) {
    }
    return 0;
}
