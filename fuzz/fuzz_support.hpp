// What the libFuzzer harnesses share: the input written to a scratch file (the parsers under test
// take paths, as the tools do), and the rule that decides what counts as a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <unistd.h>

namespace stereo::fuzz {

// A file of this process in the temporary folder, rewritten for every input and removed at exit.
class ScratchFile {
  public:
    explicit ScratchFile(const std::string& name)
        : path_(std::filesystem::temp_directory_path() /
                ("stereo_fuzz_" + std::to_string(::getpid()) + "_" + name)) {}
    ~ScratchFile() {
        std::error_code ignored;
        std::filesystem::remove(path_, ignored);
    }
    ScratchFile(const ScratchFile&) = delete;
    ScratchFile& operator=(const ScratchFile&) = delete;

    const std::filesystem::path& write(const std::uint8_t* data, std::size_t size) {
        std::ofstream out(path_, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
        out.close();
        if (!out) {
            std::fprintf(stderr, "fuzz: cannot write %s\n", path_.c_str());
            std::abort();
        }
        return path_;
    }
    const std::filesystem::path& path() const { return path_; }

  private:
    std::filesystem::path path_;
};

// Runs `parse`. The documented failures of the parsers (docs/reliability.md) are
// std::invalid_argument (bad content) and std::runtime_error (unreadable), each with a one-line
// message; anything else escaping (cv::Exception, std::bad_alloc, std::out_of_range, ...) or a
// multi-line or empty message is a finding and aborts, so libFuzzer keeps the input.
inline void expect_one_line(const char* what, const std::string& message) {
    if (message.empty() || message.find('\n') != std::string::npos) {
        std::fprintf(stderr, "fuzz: %s: malformed message \"%s\"\n", what, message.c_str());
        std::abort();
    }
}

template <class Parse>
void expect_documented_errors(const char* what, Parse&& parse) {
    try {
        parse();
    } catch (const std::runtime_error& error) {
        expect_one_line(what, error.what());
    } catch (const std::invalid_argument& error) {
        expect_one_line(what, error.what());
    } catch (const std::exception& error) {
        std::fprintf(stderr, "fuzz: %s: undocumented exception: %s\n", what, error.what());
        std::abort();
    }
}

}  // namespace stereo::fuzz
