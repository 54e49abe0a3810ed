// Outputs that lose nothing: atomic replacement, untouched destinations on failure, refused
// output/input collisions (stereo_io/output.hpp).
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

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
    static fs::path write_to(const fs::path& path, const std::string& text) {
        write(path, text);
        return path;
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

// A file written by another library by name (the FST tracer): a file with the destination's
// extension inside a private folder (mode 0700) beside the destination, renamed over the
// destination only on commit; the folder goes with whatever else the writer left in it.
TEST_F(Output, StagedOutputReplacesOnlyOnCommit) {
    const fs::path file = folder_ / "run.txt";
    write(file, "previous");
    {
        StagedOutput staged(file);
        const fs::path privat = staged.path().parent_path();
        EXPECT_EQ(privat.parent_path(), fs::absolute(folder_));
        EXPECT_EQ(privat.filename().string().rfind(".run.txt.", 0), 0U);
        struct stat status {};
        ASSERT_EQ(::lstat(privat.c_str(), &status), 0);
        EXPECT_TRUE(S_ISDIR(status.st_mode));
        EXPECT_EQ(status.st_mode & 0777, 0700U);
        EXPECT_EQ(staged.path().extension(), ".txt");
        write(staged.path(), "new text");
        write(staged.path().string() + ".hier", "a side file of the writer");
        EXPECT_EQ(read(file), "previous");  // not before the commit
        staged.commit();
        EXPECT_THROW(staged.commit(), std::logic_error);
    }
    EXPECT_EQ(read(file), "new text");
    EXPECT_EQ(files_in_folder(), 1U);  // the private folder and the side file are gone
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
    StagedOutput never_written(folder_ / "new.fst");
    EXPECT_THROW(never_written.commit(), std::runtime_error);
}

// A file the size of fstapi's header block (329 bytes after its type byte) declaring
// `value_blocks` value-change blocks, then those blocks, a geometry and a hierarchy block.
std::string fake_fst(std::uint64_t declared, int value_blocks) {
    const auto block = [](int type, std::size_t payload) {
        std::string bytes(1, static_cast<char>(type));
        const std::uint64_t length = payload + 8;
        for (int shift = 56; shift >= 0; shift -= 8) {
            bytes += static_cast<char>((length >> shift) & 0xff);
        }
        return bytes + std::string(payload, 'x');
    };
    std::string header = block(0, 321);
    for (int i = 0; i < 8; ++i) {
        header[65 + i] = static_cast<char>((declared >> (56 - 8 * i)) & 0xff);
    }
    std::string file = header;
    for (int i = 0; i < value_blocks; ++i) {
        file += block(1, 100);
    }
    return file + block(3, 20) + block(4, 50);
}

// The libraries that write by name ignore failed writes; the staged file's own structure shows
// what is missing, and such a file never replaces the destination.
TEST_F(Output, StagedOutputRefusesAnIncompleteFstOrAvi) {
    const fs::path trace = previous_trace();
    const std::string whole = fake_fst(2, 2);
    EXPECT_NO_THROW(check_fst_complete(write_to(folder_ / "whole.fst", whole), trace));
    for (const std::string& broken :
         {whole.substr(0, whole.size() - 1), whole.substr(0, 400), fake_fst(3, 2),
          std::string("\xff") + whole.substr(1), std::string()}) {
        {
            StagedOutput staged(trace);
            write(staged.path(), broken);
            EXPECT_THROW(staged.commit(), std::runtime_error);
        }
        EXPECT_EQ(read(trace), kPreviousTrace);
    }
    const auto riff = [](const std::string& form, std::uint32_t length, std::size_t present) {
        std::string bytes = "RIFF";
        for (int i = 0; i < 4; ++i) {
            bytes += static_cast<char>((length >> (8 * i)) & 0xff);
        }
        return bytes + form + std::string(present, 'm');
    };
    const fs::path video = folder_ / "v.avi";
    EXPECT_NO_THROW(check_avi_complete(write_to(folder_ / "a.avi", riff("AVI ", 104, 100)), video));
    EXPECT_NO_THROW(check_avi_complete(
        write_to(folder_ / "b.avi", riff("AVI ", 12, 8) + riff("AVIX", 20, 16)), video));
    EXPECT_THROW(check_avi_complete(write_to(folder_ / "c.avi", riff("AVI ", 104, 60)), video),
                 std::runtime_error);
    EXPECT_THROW(
        check_avi_complete(write_to(folder_ / "d.avi", riff("AVI ", 12, 8) + "RIF"), video),
        std::runtime_error);
    EXPECT_THROW(check_avi_complete(write_to(folder_ / "e.avi", ""), video), std::runtime_error);
}

// NAME_MAX is 255 bytes: a 250-byte output name is legal, its temporary's name is cut to fit.
TEST_F(Output, LongestNamesStillWork) {
    const fs::path file = folder_ / (std::string(251, 'n') + ".png");
    write_file_atomic(file, "long");
    EXPECT_EQ(read(file), "long");
    EXPECT_NO_THROW(check_can_stage(file));
    {
        StagedOutput staged(folder_ / (std::string(251, 't') + ".fst"));
        write(staged.path(), "x");
    }
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

// An output inside a folder the command reads is refused, whatever its spelling and whether or
// not it exists yet, and so is one over a file outside that a link inside the folder leads to.
TEST_F(Output, OutputInsideAnInputFolderIsRefused) {
    const fs::path sequence = folder_ / "seq";
    fs::create_directories(sequence / "image_l");
    write(sequence / "image_l" / "000000.png", "frame");
    write(sequence / "calib.txt", "calibration");
    const fs::path outside = folder_ / "poses.txt";
    write(outside, "poses");
    fs::create_symlink(outside, sequence / "poses.txt");
    fs::create_directory_symlink(sequence, folder_ / "seq_link");
    const Inputs inputs{.folders = {sequence}};
    for (const fs::path& output :
         {sequence / "image_l" / "000000.png", sequence / "image_l" / "new.png",
          sequence / "new" / "deeper" / "x.png", folder_ / "seq_link" / "calib.txt",
          folder_ / "seq_link" / "new.txt", outside, sequence / "image_l" / ".." / "x.txt"}) {
        EXPECT_THROW(check_outputs({output}, inputs), std::invalid_argument) << output;
    }
    EXPECT_NO_THROW(check_outputs({folder_ / "map.png", folder_ / "seq2" / "x"}, inputs));
    // A named input that is a folder counts as one; a hard link to a frame is the frame.
    EXPECT_THROW(check_outputs({sequence / "x.png"}, {.files = {sequence}}), std::invalid_argument);
    fs::create_hard_link(sequence / "image_l" / "000000.png", folder_ / "hard.png");
    EXPECT_THROW(check_outputs({folder_ / "hard.png"}, inputs), std::invalid_argument);
}

// Runs `child` in a forked process (the process-wide guards stay out of this one) and returns
// its wait status.
template <typename Child>
int in_child(Child child) {
    const pid_t pid = ::fork();
    if (pid == 0) {
        child();
        ::_exit(0);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    return status;
}

// The guards remove every live temporary on a caught signal, then the process ends by that
// signal (so its parent still sees it); a signal ignored before (nohup) stays ignored.
TEST_F(Output, CaughtSignalsRemoveTheTemporaries) {
    const fs::path trace = previous_trace();
    for (const int signal_number : {SIGTERM, SIGINT, SIGHUP, SIGQUIT, SIGALRM}) {
        int ready[2];
        ASSERT_EQ(::pipe(ready), 0);
        const pid_t pid = ::fork();
        if (pid == 0) {
            const rlimit no_core{0, 0};
            ::setrlimit(RLIMIT_CORE, &no_core);
            install_process_guards("test_output");
            StagedOutput staged(trace);
            write(staged.path(), std::string(100000, 't'));
            write(staged.path().string() + ".hier", "side file");
            StagedOutput second(folder_ / "other.fst");
            write(second.path(), "another");
            const char byte = 1;
            (void)!::write(ready[1], &byte, 1);
            for (;;) {
                ::pause();
            }
        }
        char byte = 0;
        ASSERT_EQ(::read(ready[0], &byte, 1), 1);
        ::close(ready[0]);
        ::close(ready[1]);
        ASSERT_EQ(::kill(pid, signal_number), 0);
        int status = 0;
        ASSERT_EQ(::waitpid(pid, &status, 0), pid);
        ASSERT_TRUE(WIFSIGNALED(status)) << signal_number;
        EXPECT_EQ(WTERMSIG(status), signal_number);
        EXPECT_EQ(read(trace), kPreviousTrace);
        EXPECT_EQ(files_in_folder(), 1U) << "a temporary survived signal " << signal_number;
    }
    const int status = in_child([] {
        std::signal(SIGHUP, SIG_IGN);
        install_process_guards("test_output");
        ::raise(SIGHUP);
        ::_exit(7);
    });
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 7);
}

// What a SIGKILL leaves (a process that ended without its destructors) is removed by the next
// process that writes into the folder: only entries of dead processes of this machine.
TEST_F(Output, SweepRemovesOnlyWhatDeadProcessesLeft) {
    const int status = in_child([this] {
        StagedOutput staged(folder_ / "killed.fst");
        write(staged.path(), "left behind");
        ::_exit(0);  // as if killed: no destructor runs
    });
    ASSERT_TRUE(WIFEXITED(status));
    std::vector<fs::path> entries(fs::directory_iterator(folder_), fs::directory_iterator{});
    ASSERT_EQ(entries.size(), 1U);
    const std::string left = entries[0].filename().string();  // ".killed.fst.PID-TAG.XXXXXX"
    const std::size_t dot = left.rfind('.');
    const std::size_t dash = left.rfind('-');
    const std::size_t pid_at = left.rfind('.', dash) + 1;
    const std::string tag = left.substr(dash + 1, dot - dash - 1);
    const auto named = [&](const std::string& pid, const std::string& with_tag,
                           const std::string& random) {
        return folder_ / (left.substr(0, pid_at) + pid + "-" + with_tag + "." + random);
    };
    const std::string dead = left.substr(pid_at, dash - pid_at);
    write(named(dead, tag, "aaaaaa"), "a file left behind");
    const fs::path victim = folder_ / "victim.txt";
    write(victim, "not to be touched");
    fs::create_symlink(victim, named(dead, tag, "bbbbbb"));
    const fs::path live = named(std::to_string(::getppid()), tag, "cccccc");  // alive
    write(live, "a live process's temporary");
    std::string other_tag = tag;
    other_tag[0] = other_tag[0] == '0' ? '1' : '0';
    const fs::path foreign = named(dead, other_tag, "dddddd");
    write(foreign, "another machine's temporary");
    write(folder_ / ".plain.txt.swp", "not ours");
    EXPECT_EQ(sweep_stale_temporaries(folder_), 3);
    EXPECT_FALSE(fs::exists(entries[0]));
    EXPECT_FALSE(fs::exists(named(dead, tag, "aaaaaa")));
    EXPECT_FALSE(fs::is_symlink(named(dead, tag, "bbbbbb")));
    EXPECT_EQ(read(victim), "not to be touched");
    EXPECT_TRUE(fs::exists(live));
    EXPECT_TRUE(fs::exists(foreign));
    EXPECT_TRUE(fs::exists(folder_ / ".plain.txt.swp"));
}

// The last line of defence behind check_outputs: with the guards installed, a write that would
// replace a file the process read is refused, and the file is kept.
TEST_F(Output, AFileTheProcessReadIsNeverReplaced) {
    const fs::path calibration = folder_ / "calib.txt";
    write(calibration, "P0: 1 2 3\n");
    const int status = in_child([&] {
        install_process_guards("test_output");
        (void)read_text_file(calibration, "calibration file");
        try {
            write_file_atomic(calibration, "replaced");
        } catch (const std::invalid_argument&) {
            ::_exit(3);
        }
        ::_exit(4);
    });
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 3);
    EXPECT_EQ(read(calibration), "P0: 1 2 3\n");
    EXPECT_EQ(files_in_folder(), 1U);
}

}  // namespace
}  // namespace stereo::io
