// Outputs that lose nothing: atomic replacement, untouched destinations on failure, refused
// output/input collisions (stereo_io/output.hpp).
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include "stereo_io/io.hpp"
#include "stereo_io/output.hpp"
#include "stereo_io/text_file.hpp"
#include "temp_folder.hpp"

namespace stereo::io {
namespace {
namespace fs = std::filesystem;

class Output : public ::testing::Test {
  protected:
    static std::string read(const fs::path& path) {
        std::ifstream in(path, std::ios::binary);
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }
    static void write(const fs::path& path, const std::string& text) {
        std::ofstream(path, std::ios::binary) << text;
    }
    // A trace already at the destination of the staged-output tests.
    static constexpr const char* kPreviousTrace = "previous trace";
    fs::path previous_trace() const {
        const fs::path file = folder_ / "run.fst";
        write(file, kPreviousTrace);
        return file;
    }
    std::size_t files_in_folder() const {
        return static_cast<std::size_t>(
            std::distance(fs::directory_iterator(folder_), fs::directory_iterator()));
    }
    const test::TempFolder temp_;
    const fs::path& folder_ = temp_.path();
};

TEST_F(Output, WritesAndReplaces) {
    const fs::path file = folder_ / "a.bin";
    write_file_atomic(file, "first");
    EXPECT_EQ(read(file), "first");
    write_file_atomic(file, "second, longer");
    EXPECT_EQ(read(file), "second, longer");
    EXPECT_EQ(files_in_folder(), 1U);  // no temporary file left
}

// A FIFO (like /dev/null, a device) named as an output: renaming over it would replace it with a
// regular file, so it is refused up front (check_writable_location) and by the writer.
TEST_F(Output, NonRegularDestinationIsRefusedAndKept) {
    const fs::path fifo = folder_ / "pipe.png";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
    EXPECT_THROW(check_writable_location(fifo), std::runtime_error);
    EXPECT_THROW(write_file_atomic(fifo, "bytes"), std::runtime_error);
    EXPECT_THROW(write_files_atomic({{folder_ / "a.png", "a"}, {fifo, "b"}}), std::runtime_error);
    EXPECT_TRUE(fs::is_fifo(fifo));
    EXPECT_FALSE(fs::exists(folder_ / "a.png"));  // all or nothing
    EXPECT_EQ(files_in_folder(), 1U);             // and no temporary file left
}

TEST_F(Output, OutputFolderMustExistOrHaveAParent) {
    EXPECT_NO_THROW(check_output_folder(folder_));
    EXPECT_NO_THROW(check_output_folder(folder_ / "new"));
    EXPECT_THROW(check_output_folder(folder_ / "none" / "new"), std::runtime_error);
    write(folder_ / "file", "x");
    EXPECT_THROW(check_output_folder(folder_ / "file"), std::runtime_error);
}

// Calibration, pose and list files are read whole, bounded, and only when they are regular
// files: a FIFO used to block in the open and /dev/zero to be read without end.
TEST_F(Output, TextInputsAreRegularBoundedFiles) {
    const fs::path text = folder_ / "calib.txt";
    write(text, "P0: 1 2 3\n");
    EXPECT_EQ(read_text_file(text, "calibration file"), "P0: 1 2 3\n");
    EXPECT_THROW((void)read_text_file(text, "calibration file", 4), std::invalid_argument);
    EXPECT_THROW((void)read_text_file(folder_ / "none.txt", "calibration file"),
                 std::runtime_error);
    EXPECT_THROW((void)read_text_file(folder_, "calibration file"), std::runtime_error);
    EXPECT_THROW((void)read_text_file("/dev/zero", "calibration file"), std::runtime_error);
    const fs::path fifo = folder_ / "pipe.txt";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
    EXPECT_THROW((void)read_text_file(fifo, "pose file"), std::runtime_error);
}

TEST_F(Output, MissingFolderWritesNothing) {
    EXPECT_THROW(write_file_atomic(folder_ / "none" / "a.bin", "x"), std::runtime_error);
    EXPECT_FALSE(fs::exists(folder_ / "none"));
}

TEST_F(Output, ReadOnlyDestinationIsKept) {
    if (::geteuid() == 0) {
        GTEST_SKIP() << "root may write read-only files";
    }
    const fs::path file = folder_ / "a.bin";
    write(file, "keep me");
    fs::permissions(file, fs::perms::owner_read);
    EXPECT_THROW(write_file_atomic(file, "new"), std::runtime_error);
    EXPECT_EQ(read(file), "keep me");
}

TEST_F(Output, FailedWriteLeavesThePreviousFile) {
    // A file-size limit makes the write fail part-way (EFBIG), as a full disk would.
    const fs::path file = folder_ / "a.bin";
    write(file, "previous");
    rlimit old{};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
    const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit small = old;
    small.rlim_cur = 64;
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
    bool threw = false;
    try {
        write_file_atomic(file, std::string(10000, 'x'));
    } catch (const std::runtime_error&) {
        threw = true;
    }
    ::setrlimit(RLIMIT_FSIZE, &old);
    std::signal(SIGXFSZ, old_handler);
    EXPECT_TRUE(threw);
    EXPECT_EQ(read(file), "previous");
    EXPECT_EQ(files_in_folder(), 1U);
}

// A file written by another library by name (the FST tracer): a hidden temporary with the
// destination's extension, renamed over the destination only on commit.
TEST_F(Output, StagedOutputReplacesOnlyOnCommit) {
    const fs::path file = previous_trace();
    {
        StagedOutput staged(file);
        EXPECT_EQ(staged.path().parent_path(), folder_);
        EXPECT_EQ(staged.path().extension(), ".fst");
        EXPECT_EQ(staged.path().filename().string().rfind(".run.", 0), 0U);
        write(staged.path(), "new trace");
        EXPECT_EQ(read(file), kPreviousTrace);  // not before the commit
        staged.commit();
        EXPECT_THROW(staged.commit(), std::logic_error);
    }
    EXPECT_EQ(read(file), "new trace");
    EXPECT_EQ(files_in_folder(), 1U);
}

TEST_F(Output, StagedOutputNotCommittedLeavesTheDestination) {
    const fs::path file = previous_trace();
    {
        StagedOutput staged(file);
        write(staged.path(), "half a trace");
    }  // an error before the commit: the temporary goes, the old trace stays
    EXPECT_EQ(read(file), kPreviousTrace);
    EXPECT_EQ(files_in_folder(), 1U);
    { StagedOutput staged(folder_ / "new.fst"); }
    EXPECT_FALSE(fs::exists(folder_ / "new.fst"));
    EXPECT_EQ(files_in_folder(), 1U);
}

TEST_F(Output, StagedOutputRefusesWhatItCannotReplace) {
    EXPECT_THROW(StagedOutput(folder_ / "none" / "t.fst"), std::runtime_error);
    const fs::path fifo = folder_ / "pipe.fst";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_THROW(StagedOutput{fifo}, std::runtime_error);
    EXPECT_EQ(files_in_folder(), 1U);
    if (::geteuid() != 0) {
        const fs::path file = folder_ / "ro.fst";
        write(file, "keep me");
        fs::permissions(file, fs::perms::owner_read);
        EXPECT_THROW(StagedOutput{file}, std::runtime_error);
        EXPECT_EQ(read(file), "keep me");
    }
}

TEST_F(Output, SeveralFilesAllOrNothing) {
    const fs::path a = folder_ / "a.png";
    write(a, "old a");
    // The third destination's folder is missing: nothing may change, no temporary file stays.
    EXPECT_THROW(
        write_files_atomic(
            {{a, "new a"}, {folder_ / "b.png", "new b"}, {folder_ / "none" / "c.png", "new c"}}),
        std::runtime_error);
    EXPECT_EQ(read(a), "old a");
    EXPECT_FALSE(fs::exists(folder_ / "b.png"));
    EXPECT_EQ(files_in_folder(), 1U);
    write_files_atomic({{a, "new a"}, {folder_ / "b.png", "new b"}});
    EXPECT_EQ(read(a), "new a");
    EXPECT_EQ(read(folder_ / "b.png"), "new b");
}

TEST_F(Output, OutputEqualToAnInputIsRefused) {
    const fs::path input = folder_ / "left.png";
    write(input, "image");
    EXPECT_THROW(check_outputs_distinct({input}, {input}), std::invalid_argument);
    // Another spelling of the same path, and a symbolic link to it.
    EXPECT_THROW(check_outputs_distinct({folder_ / "." / "left.png"}, {input}),
                 std::invalid_argument);
    fs::create_symlink(input, folder_ / "link.png");
    EXPECT_THROW(check_outputs_distinct({folder_ / "link.png"}, {input}), std::invalid_argument);
    EXPECT_NO_THROW(check_outputs_distinct({folder_ / "out.png"}, {input, fs::path()}));
}

TEST_F(Output, CollidingOutputsAreRefused) {
    EXPECT_THROW(check_outputs_distinct({folder_ / "o.png", folder_ / "x" / ".." / "o.png"}, {}),
                 std::invalid_argument);
    EXPECT_NO_THROW(check_outputs_distinct({folder_ / "o.png", fs::path(), folder_ / "p.png"}, {}));
}

}  // namespace
}  // namespace stereo::io
