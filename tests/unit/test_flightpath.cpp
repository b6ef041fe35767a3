// Unit tests for pacifica::tools::FlightPath: parsing the flight CSV format (docs/FLIGHT_FORMAT.md), every
// error it reports (file:line prefix and wording), sampling between and beyond samples, and the shipped demo
// flight (tools/data/demo_flight.csv) having the shape the demo relies on.
#include <FlightPath.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

using pacifica::Pose;
using pacifica::tools::FlightError;
using pacifica::tools::FlightPath;

constexpr const char* HEADER = "time_s,x_m,y_m,z_m,heading_deg,pitch_deg,roll_deg\n";

// Parses text that must fail and returns the error message ("" if it did not throw: the caller's
// EXPECT on the message then fails with a readable diff).
std::string parseError(const std::string& text, const std::string& name = "f.csv") {
    try {
        FlightPath::parse(text, name);
    } catch (const FlightError& e) {
        return e.what();
    }
    return "";
}

// Smallest difference between two angles in degrees, in [0, 180].
double angleDistance(double a, double b) {
    const double d = std::fmod(std::abs(a - b), 360.0);
    return std::min(d, 360.0 - d);
}

std::filesystem::path sourceDir() {
    if (const char* env = std::getenv("PACIFICA_SOURCE_DIR"); env && *env) {
        return env;
    }
    // tests/unit/test_flightpath.cpp -> repository root.
    return std::filesystem::path(__FILE__).parent_path().parent_path().parent_path();
}

TEST(FlightPath, ParsesGoodTextWithCommentsBomCrlfAndSpaces) {
    const std::string text = "\xEF\xBB\xBF# a comment\r\n"
                             "\r\n"
                             " time_s , x_m,y_m ,z_m,heading_deg,pitch_deg,\troll_deg \r\n"
                             "0,1,2,3,90,0,0\r\n"
                             "# between samples\r\n"
                             "  1.5 , -10.25, 2e2, -3 , 359.5, -12.5, +45\r\n"
                             "\n";
    const FlightPath path = FlightPath::parse(text, "good.csv");
    ASSERT_EQ(path.samples().size(), 2u);
    EXPECT_EQ(path.startTime(), 0.0);
    EXPECT_EQ(path.endTime(), 1.5);
    const Pose& p = path.samples()[1].pose;
    EXPECT_EQ(p.position.x, -10.25);
    EXPECT_EQ(p.position.y, 200.0);
    EXPECT_EQ(p.position.z, -3.0); // below sea level is allowed
    EXPECT_EQ(p.headingDeg, 359.5);
    EXPECT_EQ(p.pitchDeg, -12.5);
    EXPECT_EQ(p.rollDeg, 45.0);
    EXPECT_EQ(path.samples()[0].pose.position.x, 1.0);
}

TEST(FlightPath, PoseAtInterpolatesWithinTheRightSegment) {
    const std::string text = std::string(HEADER) + "0,0,0,100,10,0,0\n"
                                                   "2,100,50,200,30,0,0\n"
                                                   "4,100,50,0,30,20,0\n";
    const FlightPath path = FlightPath::parse(text, "mid.csv");

    const Pose mid = path.poseAt(1.0); // halfway through the first segment
    EXPECT_NEAR(mid.position.x, 50.0, 1e-9);
    EXPECT_NEAR(mid.position.y, 25.0, 1e-9);
    EXPECT_NEAR(mid.position.z, 150.0, 1e-9);
    EXPECT_NEAR(angleDistance(mid.headingDeg, 20.0), 0.0, 1e-6); // same axis: slerp is linear in angle
    EXPECT_NEAR(mid.pitchDeg, 0.0, 1e-6);
    EXPECT_NEAR(mid.rollDeg, 0.0, 1e-6);

    const Pose quarter = path.poseAt(0.5);
    EXPECT_NEAR(quarter.position.x, 25.0, 1e-9);
    EXPECT_NEAR(quarter.position.z, 125.0, 1e-9);
    EXPECT_NEAR(angleDistance(quarter.headingDeg, 15.0), 0.0, 1e-6);

    const Pose second = path.poseAt(3.0); // second segment: only z and pitch change
    EXPECT_NEAR(second.position.x, 100.0, 1e-9);
    EXPECT_NEAR(second.position.z, 100.0, 1e-9);
    EXPECT_NEAR(second.pitchDeg, 10.0, 1e-6);
    EXPECT_NEAR(angleDistance(second.headingDeg, 30.0), 0.0, 1e-6);

    const Pose exact = path.poseAt(2.0); // exactly on a sample
    EXPECT_NEAR(exact.position.z, 200.0, 1e-9);
}

TEST(FlightPath, PoseAtTakesTheShortArcAcrossNorth) {
    const FlightPath path =
        FlightPath::parse(std::string(HEADER) + "0,0,0,10,350,0,0\n1,0,0,10,10,0,0\n", "n.csv");
    EXPECT_NEAR(angleDistance(path.poseAt(0.5).headingDeg, 0.0), 0.0, 1e-6);
}

TEST(FlightPath, PoseAtClampsToTheFlight) {
    const FlightPath path =
        FlightPath::parse(std::string(HEADER) + "10,1,2,3,0,0,0\n20,4,5,6,0,0,0\n", "c.csv");
    EXPECT_EQ(path.poseAt(-100.0).position, glm::dvec3(1, 2, 3));
    EXPECT_EQ(path.poseAt(10.0).position, glm::dvec3(1, 2, 3));
    EXPECT_EQ(path.poseAt(20.0).position, glm::dvec3(4, 5, 6));
    EXPECT_EQ(path.poseAt(1e9).position, glm::dvec3(4, 5, 6));
    EXPECT_EQ(path.poseAt(std::nan("")).position, glm::dvec3(1, 2, 3));
}

TEST(FlightPathErrors, MissingFile) {
    const std::filesystem::path missing =
        std::filesystem::temp_directory_path() / "pacifica-no-such-flight.csv";
    try {
        FlightPath::load(missing);
        FAIL() << "expected FlightError";
    } catch (const FlightError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(missing.string() + ": cannot open flight file", 0), 0u)
            << e.what();
        EXPECT_EQ(e.line(), 0);
        EXPECT_EQ(e.file(), missing.string());
    }
}

TEST(FlightPathErrors, DirectoryIsNotAFlight) {
    const std::string dir = std::filesystem::temp_directory_path().string();
    try {
        FlightPath::load(dir);
        FAIL() << "expected FlightError";
    } catch (const FlightError& e) {
        EXPECT_NE(std::string(e.what()).find(": cannot open flight file"), std::string::npos) << e.what();
    }
}

TEST(FlightPathErrors, EmptyFileOrNoHeader) {
    EXPECT_EQ(
        parseError("", "e.csv"),
        "e.csv: empty flight file: expected header 'time_s,x_m,y_m,z_m,heading_deg,pitch_deg,roll_deg'");
    EXPECT_EQ(parseError("# only a comment\n\n   \n", "e.csv").rfind("e.csv: empty flight file", 0), 0u);
    EXPECT_EQ(parseError("\xEF\xBB\xBF", "e.csv").rfind("e.csv: empty flight file", 0), 0u);
}

TEST(FlightPathErrors, WrongHeader) {
    const std::string msg = parseError("# c\ntime,x,y,z,h,p,r\n0,0,0,0,0,0,0\n");
    EXPECT_EQ(msg, "f.csv:2: expected header 'time_s,x_m,y_m,z_m,heading_deg,pitch_deg,roll_deg', "
                   "got 'time,x,y,z,h,p,r'");
    // A sample where the header should be, and a header with an extra column.
    EXPECT_EQ(parseError("0,0,0,0,0,0,0\n").rfind("f.csv:1: expected header", 0), 0u);
    EXPECT_EQ(parseError("time_s,x_m,y_m,z_m,heading_deg,pitch_deg,roll_deg,extra\n")
                  .rfind("f.csv:1: expected header", 0),
              0u);
}

TEST(FlightPathErrors, WrongFieldCount) {
    EXPECT_EQ(parseError(std::string(HEADER) + "0,0,0,0,0,0,0\n1,0,0,0,0,0\n"),
              "f.csv:3: expected 7 fields, got 6");
    EXPECT_EQ(parseError(std::string(HEADER) + "0,0,0,0,0,0,0,0\n"), "f.csv:2: expected 7 fields, got 8");
}

TEST(FlightPathErrors, NonNumericFieldNamesTheColumn) {
    EXPECT_EQ(parseError(std::string(HEADER) + "0,0,0,abc,0,0,0\n"),
              "f.csv:2: field 'z_m' is not a number: 'abc'");
    EXPECT_EQ(parseError(std::string(HEADER) + "0,0,0,0,0,0,0\n1,1.5x,0,0,0,0,0\n"),
              "f.csv:3: field 'x_m' is not a number: '1.5x'"); // trailing junk
    EXPECT_EQ(parseError(std::string(HEADER) + "0,0,,0,0,0,0\n"), "f.csv:2: field 'y_m' is not a number: ''");
    EXPECT_EQ(parseError(std::string(HEADER) + "0,0,0,0,1 2,0,0\n"),
              "f.csv:2: field 'heading_deg' is not a number: '1 2'");
    EXPECT_EQ(parseError(std::string(HEADER) + "0,0,0,0,0,0,1,5\n"), "f.csv:2: expected 7 fields, got 8");
    EXPECT_EQ(parseError(std::string(HEADER) + "0,0,0,0,0,0,++1\n"),
              "f.csv:2: field 'roll_deg' is not a number: '++1'");
}

TEST(FlightPathErrors, NonFiniteField) {
    EXPECT_EQ(parseError(std::string(HEADER) + "0,0,0,0,0,nan,0\n"),
              "f.csv:2: field 'pitch_deg' is not finite");
    EXPECT_EQ(parseError(std::string(HEADER) + "0,0,0,0,0,0,0\n1,0,0,0,-inf,0,0\n"),
              "f.csv:3: field 'heading_deg' is not finite");
    EXPECT_EQ(parseError(std::string(HEADER) + "0,1e999,0,0,0,0,0\n"),
              "f.csv:2: field 'x_m' is out of range: '1e999'");
}

TEST(FlightPathErrors, PitchBeyondNinety) {
    EXPECT_EQ(parseError(std::string(HEADER) + "0,0,0,0,0,90.5,0\n"),
              "f.csv:2: field 'pitch_deg' must be within [-90, 90], got 90.5");
    EXPECT_EQ(parseError(std::string(HEADER) + "0,0,0,0,0,-91,0\n")
                  .rfind("f.csv:2: field 'pitch_deg' must be within", 0),
              0u);
    // Exactly +-90 is allowed.
    EXPECT_NO_THROW(FlightPath::parse(std::string(HEADER) + "0,0,0,0,0,90,0\n1,0,0,0,0,-90,0\n", "f.csv"));
}

TEST(FlightPathErrors, TimeNotStrictlyIncreasing) {
    EXPECT_EQ(parseError(std::string(HEADER) + "0,0,0,0,0,0,0\n# c\n0,0,0,0,0,0,0\n"),
              "f.csv:4: time_s must be strictly increasing: 0 does not follow 0 (line 2)");
    EXPECT_EQ(parseError(std::string(HEADER) + "0,0,0,0,0,0,0\n2.5,0,0,0,0,0,0\n2,0,0,0,0,0,0\n"),
              "f.csv:4: time_s must be strictly increasing: 2 does not follow 2.5 (line 3)");
}

TEST(FlightPathErrors, FewerThanTwoSamples) {
    EXPECT_EQ(parseError(std::string(HEADER)), "f.csv: expected at least 2 samples, got 0");
    EXPECT_EQ(parseError(std::string(HEADER) + "0,0,0,0,0,0,0\n"),
              "f.csv: expected at least 2 samples, got 1");
}

TEST(FlightPathErrors, LoadReportsTheFilePathAndLine) {
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() /
        ("pacifica-test-flight-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         ".csv");
    {
        std::FILE* f = std::fopen(file.string().c_str(), "wb");
        ASSERT_NE(f, nullptr);
        const std::string text = std::string(HEADER) + "0,0,0,0,0,0,0\n1,0,0,zz,0,0,0\n";
        std::fwrite(text.data(), 1, text.size(), f);
        std::fclose(f);
    }
    try {
        FlightPath::load(file);
        ADD_FAILURE() << "expected FlightError";
    } catch (const FlightError& e) {
        EXPECT_EQ(std::string(e.what()), file.string() + ":3: field 'z_m' is not a number: 'zz'");
        EXPECT_EQ(e.line(), 3);
        EXPECT_EQ(e.message(), "field 'z_m' is not a number: 'zz'");
    }
    std::filesystem::remove(file);
}

TEST(DemoFlight, LoadsAndHasTheShapeTheDemoNeeds) {
    const std::filesystem::path file = sourceDir() / "tools" / "data" / "demo_flight.csv";
    const FlightPath path = FlightPath::load(file);
    const auto& samples = path.samples();
    EXPECT_GT(samples.size(), 100u);

    double minZ = samples.front().pose.position.z;
    double maxZ = minZ;
    double maxAbsRoll = 0.0;
    for (const auto& s : samples) {
        minZ = std::min(minZ, s.pose.position.z);
        maxZ = std::max(maxZ, s.pose.position.z);
        maxAbsRoll = std::max(maxAbsRoll, std::abs(s.pose.rollDeg));
        EXPECT_GE(s.pose.headingDeg, 0.0);
        EXPECT_LT(s.pose.headingDeg, 360.0);
    }
    EXPECT_GT(maxZ, 3000.0);     // the climb reaches altitude
    EXPECT_LT(minZ, 40.0);       // the low pass skims the sea
    EXPECT_GT(maxAbsRoll, 30.0); // the turn is banked
    EXPECT_GE(path.endTime() - path.startTime(), 50.0);
}

} // namespace
