// writeFileAtomically (engine/AtomicFile.h): the file appears whole or not at all. A write replaces the
// target; a failed one (missing directory, a target that cannot be replaced, a writer that throws) leaves the
// target as it was, leaves no temporary beside it, and names the target in its error.
#include "engine/AtomicFile.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unistd.h> // mkdtemp

namespace fs = std::filesystem;

namespace {

class AtomicFile : public ::testing::Test {
protected:
    void SetUp() override {
        std::string pattern = (fs::temp_directory_path() / "pacifica-atomic-XXXXXX").string();
        ASSERT_NE(mkdtemp(pattern.data()), nullptr);
        dir = pattern;
    }
    void TearDown() override { fs::remove_all(dir); }
    static std::string read(const fs::path& p) {
        std::ifstream in(p, std::ios::binary);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }
    size_t entries() const {
        size_t n = 0;
        for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir))
            ++n;
        return n;
    }
    fs::path dir;
};

TEST_F(AtomicFile, WritesAndReplaces) {
    const fs::path f = dir / "summary.json";
    pacifica::writeFileAtomically(f, "{\"a\": 1}\n");
    EXPECT_EQ(read(f), "{\"a\": 1}\n");
    pacifica::writeFileAtomically(f, [](std::ostream& out) { out << "second " << 2; });
    EXPECT_EQ(read(f), "second 2");
    EXPECT_EQ(entries(), 1u); // no temporary left
}

TEST_F(AtomicFile, AWriterThatThrowsLeavesTheOldFile) {
    const fs::path f = dir / "report.md";
    pacifica::writeFileAtomically(f, "old");
    EXPECT_THROW(pacifica::writeFileAtomically(f,
                                               [](std::ostream& out) {
                                                   out << "half of the new";
                                                   throw std::logic_error("the writer failed");
                                               }),
                 std::logic_error);
    EXPECT_EQ(read(f), "old");
    EXPECT_EQ(entries(), 1u);
}

TEST_F(AtomicFile, AMissingDirectoryIsNamedInTheError) {
    const fs::path f = dir / "missing" / "out.json";
    try {
        pacifica::writeFileAtomically(f, "x");
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(f.string() + ": cannot write"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(f));
    EXPECT_EQ(entries(), 0u);
}

// The rename fails (the target is a directory, whatever the user's rights): no temporary is left.
TEST_F(AtomicFile, AFailedRenameLeavesNoTemporary) {
    const fs::path f = dir / "frames";
    fs::create_directory(f);
    std::ofstream(f / "frame_00000.png") << "a frame";
    try {
        pacifica::writeFileAtomically(f, "x");
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(f.string() + ": cannot write: cannot rename into place"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_TRUE(fs::is_directory(f));
    EXPECT_EQ(read(f / "frame_00000.png"), "a frame");
    EXPECT_EQ(entries(), 1u);
}

} // namespace
