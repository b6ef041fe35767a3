// Unit tests for pacifica::tools::FlightPath: parsing the flight CSV format (docs/FLIGHT_FORMAT.md), every
// error it reports (file:line prefix and wording), sampling between and beyond samples, the event records
// (explosions, ship tracks and their sampling), and the shipped demo flight (tools/data/demo_flight.csv)
// having the shape and events the demo relies on.
#include <FlightPath.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

using pacifica::Pose;
using pacifica::tools::ExplosionEvent;
using pacifica::tools::FlightError;
using pacifica::tools::FlightPath;
using pacifica::tools::ShipTrack;

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

// ---------------------------------------------------------------------------------------------------------
// Event records: explosion and ship.

// Two camera samples (lines 2 and 3 after HEADER), for event tests that need a valid flight around them.
const std::string CAMERA = std::string(HEADER) + "0,0,0,20,90,0,0\n10,1500,0,20,90,0,0\n";

TEST(FlightEvents, FileWithoutEventsHasNone) {
    const FlightPath path = FlightPath::parse(CAMERA, "f.csv");
    EXPECT_TRUE(path.explosions().empty());
    EXPECT_TRUE(path.ships().empty());
    EXPECT_EQ(path.samples().size(), 2u);
}

TEST(FlightEvents, RecordsAnywhereAfterTheHeaderAndOutsideTheCameraSpan) {
    const std::string text = "# events before, between and after camera samples\n" // 1
                             "time_s,x_m,y_m,z_m,heading_deg,pitch_deg,roll_deg\n" // 2
                             "ship,alpha,-120,0,0\n"                               // 3
                             " explosion , 4.5 , 900 , -60 , 2 \r\n"               // 4
                             "0,0,0,20,90,0,0\n"                                   // 5
                             "ship,B_2-x,0,+1e3,-5.5\n"                            // 6
                             "explosion,1,10,20,0.25\n"                            // 7
                             "# a comment between records\n"                       // 8
                             "ship,alpha,-60,600,0\n"                              // 9
                             "10,1500,0,20,90,0,0\n"                               // 10
                             "explosion,4.5,-1,-2,1\n"                             // 11 (same time as 4)
                             "ship,B_2-x,100,1000,994.5\n"                         // 12
                             "ship,alpha,0,600,600\n"                              // 13
                             "explosion,200,0,0,1e-3\n";                           // 14 (after the camera)
    const FlightPath path = FlightPath::parse(text, "ev.csv");

    // The camera path is exactly the two numeric lines.
    ASSERT_EQ(path.samples().size(), 2u);
    EXPECT_EQ(path.startTime(), 0.0);
    EXPECT_EQ(path.endTime(), 10.0);

    // Explosions sorted by time; the two at 4.5 s keep their file order (lines 4, 11).
    const std::vector<ExplosionEvent>& ex = path.explosions();
    ASSERT_EQ(ex.size(), 4u);
    EXPECT_EQ(ex[0].time, 1.0);
    EXPECT_EQ(ex[0].x, 10.0);
    EXPECT_EQ(ex[0].y, 20.0);
    EXPECT_EQ(ex[0].strength, 0.25);
    EXPECT_EQ(ex[0].line, 7);
    EXPECT_EQ(ex[1].time, 4.5);
    EXPECT_EQ(ex[1].x, 900.0);
    EXPECT_EQ(ex[1].y, -60.0);
    EXPECT_EQ(ex[1].strength, 2.0);
    EXPECT_EQ(ex[1].line, 4);
    EXPECT_EQ(ex[2].time, 4.5);
    EXPECT_EQ(ex[2].x, -1.0);
    EXPECT_EQ(ex[2].line, 11);
    EXPECT_EQ(ex[3].time, 200.0);
    EXPECT_EQ(ex[3].strength, 1e-3);
    EXPECT_EQ(ex[3].line, 14);

    // Ships in order of first appearance, samples in file order even when interleaved with other records.
    const std::vector<ShipTrack>& ships = path.ships();
    ASSERT_EQ(ships.size(), 2u);
    EXPECT_EQ(ships[0].id, "alpha");
    EXPECT_EQ(ships[0].line, 3);
    ASSERT_EQ(ships[0].samples.size(), 3u);
    EXPECT_EQ(ships[0].samples[0].time, -120.0);
    EXPECT_EQ(ships[0].samples[1].time, -60.0);
    EXPECT_EQ(ships[0].samples[1].x, 600.0);
    EXPECT_EQ(ships[0].samples[2].y, 600.0);
    EXPECT_EQ(ships[0].startTime(), -120.0);
    EXPECT_EQ(ships[0].endTime(), 0.0);
    EXPECT_EQ(ships[1].id, "B_2-x");
    EXPECT_EQ(ships[1].line, 6);
    ASSERT_EQ(ships[1].samples.size(), 2u);
    EXPECT_EQ(ships[1].samples[0].x, 1000.0);
    EXPECT_EQ(ships[1].samples[0].y, -5.5);
    EXPECT_EQ(ships[1].samples[1].time, 100.0);
    EXPECT_EQ(ships[1].samples[1].y, 994.5);
}

TEST(FlightEvents, ShipIdsAreCaseSensitiveAndMayBeNumbers) {
    const FlightPath path =
        FlightPath::parse(CAMERA + "ship,a,0,0,0\nship,A,0,0,0\nship,7,0,0,0\nship,a,1,0,0\nship,A,1,0,0\n"
                                   "ship,7,1,0,0\n",
                          "f.csv");
    ASSERT_EQ(path.ships().size(), 3u);
    EXPECT_EQ(path.ships()[0].id, "a");
    EXPECT_EQ(path.ships()[1].id, "A");
    EXPECT_EQ(path.ships()[2].id, "7");
}

// A ship going east at 10 m/s for 10 s, holding still 5 s, then north at 5 m/s for 20 s.
ShipTrack lShapedShip() {
    const FlightPath path = FlightPath::parse(
        CAMERA + "ship,s,-10,-100,0\nship,s,0,0,0\nship,s,5,0,0\nship,s,25,0,100\n", "s.csv");
    return path.ships().at(0);
}

TEST(ShipTrack, PositionAtIsLinearAndClamped) {
    const ShipTrack ship = lShapedShip();
    EXPECT_EQ(ship.positionAt(-10.0), glm::dvec2(-100, 0));
    EXPECT_EQ(ship.positionAt(-7.5), glm::dvec2(-75, 0));
    EXPECT_EQ(ship.positionAt(-2.5), glm::dvec2(-25, 0));
    EXPECT_EQ(ship.positionAt(0.0), glm::dvec2(0, 0));
    EXPECT_EQ(ship.positionAt(3.0), glm::dvec2(0, 0)); // holding still
    EXPECT_EQ(ship.positionAt(15.0), glm::dvec2(0, 50));
    EXPECT_EQ(ship.positionAt(24.0), glm::dvec2(0, 95));
    EXPECT_EQ(ship.positionAt(25.0), glm::dvec2(0, 100));
    // Clamped before and after the track; NaN gives the first position.
    EXPECT_EQ(ship.positionAt(-1e9), glm::dvec2(-100, 0));
    EXPECT_EQ(ship.positionAt(1e9), glm::dvec2(0, 100));
    EXPECT_EQ(ship.positionAt(std::nan("")), glm::dvec2(-100, 0));
}

TEST(ShipTrack, VelocityAtIsThePiecewiseSegmentVelocity) {
    const ShipTrack ship = lShapedShip();
    EXPECT_EQ(ship.velocityAt(-10.0), glm::dvec2(10, 0)); // exactly at the start: first segment
    EXPECT_EQ(ship.velocityAt(-3.0), glm::dvec2(10, 0));
    EXPECT_EQ(ship.velocityAt(0.0), glm::dvec2(0, 0)); // on a sample: the segment starting there
    EXPECT_EQ(ship.velocityAt(4.999), glm::dvec2(0, 0));
    EXPECT_EQ(ship.velocityAt(5.0), glm::dvec2(0, 5));
    EXPECT_EQ(ship.velocityAt(20.0), glm::dvec2(0, 5));
    EXPECT_EQ(ship.velocityAt(25.0), glm::dvec2(0, 5)); // exactly at the end: last segment
    // Outside the track the clamped position does not move.
    EXPECT_EQ(ship.velocityAt(-10.001), glm::dvec2(0, 0));
    EXPECT_EQ(ship.velocityAt(25.001), glm::dvec2(0, 0));
    EXPECT_EQ(ship.velocityAt(std::nan("")), glm::dvec2(0, 0));
}

TEST(ShipTrack, HeadingAtFollowsTheSegmentAndKeepsItWhileStill) {
    const ShipTrack ship = lShapedShip();
    EXPECT_EQ(ship.headingAt(-5.0), 90.0); // east
    EXPECT_EQ(ship.headingAt(0.0), 90.0);  // still: keeps pointing east
    EXPECT_EQ(ship.headingAt(4.0), 90.0);  // still
    EXPECT_EQ(ship.headingAt(5.0), 0.0);   // north
    EXPECT_EQ(ship.headingAt(25.0), 0.0);  // end
    EXPECT_EQ(ship.headingAt(-1e9), 90.0); // before the track: the first segment's heading
    EXPECT_EQ(ship.headingAt(1e9), 0.0);   // after: the last segment's
    EXPECT_EQ(ship.headingAt(std::nan("")), 90.0);

    // South-west is 225; west 270; a ship that starts still takes the first moving segment's heading.
    const FlightPath path =
        FlightPath::parse(CAMERA + "ship,sw,0,0,0\nship,sw,1,-3,-3\nship,sw,2,-5,-3\n"
                                   "ship,still,0,7,7\nship,still,1,7,7\nship,still,2,7,8\n"
                                   "ship,moored,0,1,1\nship,moored,9,1,1\n",
                          "h.csv");
    const ShipTrack& sw = path.ships().at(0);
    EXPECT_NEAR(sw.headingAt(0.5), 225.0, 1e-12);
    EXPECT_EQ(sw.headingAt(1.5), 270.0);
    EXPECT_EQ(path.ships().at(1).headingAt(0.5), 0.0);
    EXPECT_EQ(path.ships().at(1).velocityAt(0.5), glm::dvec2(0, 0));
    EXPECT_EQ(path.ships().at(1).velocityAt(1.5), glm::dvec2(0, 1));
    EXPECT_EQ(path.ships().at(2).headingAt(3.0), 0.0); // never moves
    EXPECT_EQ(path.ships().at(2).positionAt(3.0), glm::dvec2(1, 1));
}

TEST(FlightEventErrors, UnknownRecordKeyword) {
    const std::string hint = "': expected a camera sample (a number first), 'explosion' or 'ship'";
    EXPECT_EQ(parseError(CAMERA + "boat,a,0,0,0\n"), "f.csv:4: unknown record 'boat" + hint);
    EXPECT_EQ(parseError(CAMERA + "Explosion,1,0,0,1\n"), "f.csv:4: unknown record 'Explosion" + hint);
    EXPECT_EQ(parseError(CAMERA + "ships\n"), "f.csv:4: unknown record 'ships" + hint);
    // A word that spells a number stays a camera sample and gets that sample's errors.
    EXPECT_EQ(parseError(CAMERA + "nan,0,0,0,0,0,0\n"), "f.csv:4: field 'time_s' is not finite");
    EXPECT_EQ(parseError(CAMERA + "inf,0,0,0,0,0,0\n"), "f.csv:4: field 'time_s' is not finite");
    // Not a word (a digit or a '-' inside): a camera sample whose time_s is not a number.
    EXPECT_EQ(parseError(CAMERA + "1x,0,0,0,0,0,0\n"), "f.csv:4: field 'time_s' is not a number: '1x'");
    EXPECT_EQ(parseError(CAMERA + "ship-1,0,0,0,0,0,0\n"),
              "f.csv:4: field 'time_s' is not a number: 'ship-1'");
}

TEST(FlightEventErrors, RecordBeforeTheHeaderIsAWrongHeader) {
    EXPECT_EQ(parseError("explosion,1,0,0,1\n" + CAMERA),
              "f.csv:1: expected header 'time_s,x_m,y_m,z_m,heading_deg,pitch_deg,roll_deg', got "
              "'explosion,1,0,0,1'");
}

TEST(FlightEventErrors, WrongFieldCount) {
    EXPECT_EQ(parseError(CAMERA + "explosion,1,0,0\n"),
              "f.csv:4: explosion record: expected 5 fields (explosion,time_s,x_m,y_m,strength), got 4");
    EXPECT_EQ(parseError(CAMERA + "explosion,1,0,0,1,9\n"),
              "f.csv:4: explosion record: expected 5 fields (explosion,time_s,x_m,y_m,strength), got 6");
    EXPECT_EQ(parseError(CAMERA + "explosion\n"),
              "f.csv:4: explosion record: expected 5 fields (explosion,time_s,x_m,y_m,strength), got 1");
    EXPECT_EQ(parseError(CAMERA + "ship,a,0,0\n"),
              "f.csv:4: ship record: expected 5 fields (ship,id,time_s,x_m,y_m), got 4");
    EXPECT_EQ(parseError(CAMERA + "ship,a,0,0,0,0\n"),
              "f.csv:4: ship record: expected 5 fields (ship,id,time_s,x_m,y_m), got 6");
}

TEST(FlightEventErrors, NotANumberNamesTheRecordAndField) {
    EXPECT_EQ(parseError(CAMERA + "explosion,t,0,0,1\n"),
              "f.csv:4: explosion field 'time_s' is not a number: 't'");
    EXPECT_EQ(parseError(CAMERA + "explosion,1,,0,1\n"),
              "f.csv:4: explosion field 'x_m' is not a number: ''");
    EXPECT_EQ(parseError(CAMERA + "explosion,1,0,5m,1\n"),
              "f.csv:4: explosion field 'y_m' is not a number: '5m'");
    EXPECT_EQ(parseError(CAMERA + "explosion,1,0,0,big\n"),
              "f.csv:4: explosion field 'strength' is not a number: 'big'");
    EXPECT_EQ(parseError(CAMERA + "ship,a,1 2,0,0\n"), "f.csv:4: ship field 'time_s' is not a number: '1 2'");
    EXPECT_EQ(parseError(CAMERA + "ship,a,0,++1,0\n"), "f.csv:4: ship field 'x_m' is not a number: '++1'");
    EXPECT_EQ(parseError(CAMERA + "ship,a,0,0,north\n"),
              "f.csv:4: ship field 'y_m' is not a number: 'north'");
}

TEST(FlightEventErrors, NotFiniteOrOutOfRange) {
    EXPECT_EQ(parseError(CAMERA + "explosion,nan,0,0,1\n"),
              "f.csv:4: explosion field 'time_s' is not finite");
    EXPECT_EQ(parseError(CAMERA + "explosion,1,0,0,inf\n"),
              "f.csv:4: explosion field 'strength' is not finite");
    EXPECT_EQ(parseError(CAMERA + "ship,a,0,-inf,0\n"), "f.csv:4: ship field 'x_m' is not finite");
    EXPECT_EQ(parseError(CAMERA + "ship,a,0,0,1e999\n"),
              "f.csv:4: ship field 'y_m' is out of range: '1e999'");
    EXPECT_EQ(parseError(CAMERA + "explosion,-1e400,0,0,1\n"),
              "f.csv:4: explosion field 'time_s' is out of range: '-1e400'");
}

TEST(FlightEventErrors, StrengthMustBePositive) {
    EXPECT_EQ(parseError(CAMERA + "explosion,1,0,0,0\n"),
              "f.csv:4: explosion field 'strength' must be > 0, got 0");
    EXPECT_EQ(parseError(CAMERA + "explosion,1,0,0,-0.5\n"),
              "f.csv:4: explosion field 'strength' must be > 0, got -0.5");
    EXPECT_EQ(parseError(CAMERA + "explosion,1,0,0,-0\n"),
              "f.csv:4: explosion field 'strength' must be > 0, got -0");
    EXPECT_NO_THROW(FlightPath::parse(CAMERA + "explosion,1,0,0,5e-324\n", "f.csv")); // smallest positive
}

TEST(FlightEventErrors, BadShipId) {
    EXPECT_EQ(parseError(CAMERA + "ship,,0,0,0\n"), "f.csv:4: ship id must match [A-Za-z0-9_-]+, got ''");
    EXPECT_EQ(parseError(CAMERA + "ship,a b,0,0,0\n"),
              "f.csv:4: ship id must match [A-Za-z0-9_-]+, got 'a b'");
    EXPECT_EQ(parseError(CAMERA + "ship,a.b,0,0,0\n"),
              "f.csv:4: ship id must match [A-Za-z0-9_-]+, got 'a.b'");
    EXPECT_EQ(parseError(CAMERA + "ship,\xC3\xA9t\xC3\xA9,0,0,0\n"),
              "f.csv:4: ship id must match [A-Za-z0-9_-]+, got '\xC3\xA9t\xC3\xA9'");
    // The id is checked before the numbers.
    EXPECT_EQ(parseError(CAMERA + "ship,#1,x,0,0\n"), "f.csv:4: ship id must match [A-Za-z0-9_-]+, got '#1'");
}

TEST(FlightEventErrors, ShipTimeNotIncreasingNamesTheShipsEarlierLine) {
    // Line 5's sample of 'a' does not follow line 4's; 'b' (line 6) is a different ship and does not count.
    EXPECT_EQ(parseError(CAMERA + "ship,a,3,0,0\nship,a,3,1,1\n"),
              "f.csv:5: ship 'a': time_s must be strictly increasing: 3 does not follow 3 (line 4)");
    EXPECT_EQ(parseError(CAMERA + "ship,a,2.5,0,0\nship,b,9,0,0\n# c\nexplosion,0,0,0,1\nship,a,2,0,0\n"),
              "f.csv:8: ship 'a': time_s must be strictly increasing: 2 does not follow 2.5 (line 4)");
    // Ship times are independent of the camera's and of other ships'.
    EXPECT_NO_THROW(
        FlightPath::parse(CAMERA + "ship,a,5,0,0\nship,b,1,0,0\nship,a,6,0,0\nship,b,2,0,0\n", "f.csv"));
}

TEST(FlightEventErrors, ShipWithOneSampleNamesTheShipAndItsLine) {
    EXPECT_EQ(parseError(CAMERA + "ship,a,0,0,0\nship,a,1,0,0\n# c\nship,lonely,0,0,0\n"),
              "f.csv:7: ship 'lonely' has 1 sample, expected at least 2");
    // Too few camera samples are reported first (the camera path is what every replay needs).
    EXPECT_EQ(parseError(std::string(HEADER) + "ship,lonely,0,0,0\n0,0,0,0,0,0,0\n"),
              "f.csv: expected at least 2 samples, got 1");
    // Several short ships: the first in file order is named.
    EXPECT_EQ(parseError(CAMERA + "ship,x,0,0,0\nship,y,0,0,0\n"),
              "f.csv:4: ship 'x' has 1 sample, expected at least 2");
    // A camera-only file is still valid: events are optional.
    EXPECT_NO_THROW(FlightPath::parse(CAMERA, "f.csv"));
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

// The demo shows at least one explosion during the flight and one ship whose wake already exists at the
// start (its track begins well before the camera's) and which sails on to the end.
TEST(DemoFlight, CarriesAnExplosionAndAShipWithHistory) {
    const FlightPath path = FlightPath::load(sourceDir() / "tools" / "data" / "demo_flight.csv");
    ASSERT_GE(path.explosions().size(), 1u);
    const ExplosionEvent& first = path.explosions().front();
    EXPECT_GT(first.time, path.startTime());
    EXPECT_LT(first.time, path.startTime() + 10.0); // during the low pass
    // Ahead of the camera when it goes off: the low pass flies east (+x).
    const Pose camera = path.poseAt(first.time);
    EXPECT_GT(first.x - camera.position.x, 200.0);
    EXPECT_LT(first.x - camera.position.x, 800.0);

    ASSERT_GE(path.ships().size(), 1u);
    const ShipTrack& ship = path.ships().front();
    EXPECT_LE(ship.startTime(), path.startTime() - 60.0);
    EXPECT_GE(ship.endTime(), path.endTime());
    const double speed = glm::length(ship.velocityAt(path.startTime()));
    EXPECT_GT(speed, 5.0);
    EXPECT_LT(speed, 20.0);
    // It turns: its heading changes by more than 30 degrees over the track.
    EXPECT_GT(angleDistance(ship.headingAt(ship.startTime()), ship.headingAt(ship.endTime())), 30.0);
}

} // namespace
