// cli::run, the top-level error handler of `stereo` and `stereo_experiments`: every exception a
// command throws becomes one "stereo: error: ..." line and the documented exit code
// (docs/cli.md), library exceptions included.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "cli_run.hpp"

namespace {

struct Outcome {
    int exit_code;
    std::string stderr_text;
};

// `stereo go` whose callback is `body`.
Outcome run_command(const std::function<void()>& body) {
    CLI::App app{"test", "stereo"};
    app.require_subcommand(1);
    app.add_subcommand("go", "run the body")->callback(body);
    std::string program = "stereo";
    std::string command = "go";
    std::vector<char*> argv = {program.data(), command.data(), nullptr};
    testing::internal::CaptureStderr();
    const int code = stereo::cli::run(app, 2, argv.data());
    return {code, testing::internal::GetCapturedStderr()};
}

void expect_one_error_line(const Outcome& outcome) {
    const std::string& text = outcome.stderr_text;
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
    EXPECT_EQ(text.rfind("stereo: error: ", 0), 0U) << text;
}

TEST(CliRun, OpenCvAssertionIsOneUsageLineWithoutTheSourceLocation) {
    const Outcome outcome = run_command([] {
        const cv::Mat empty;
        cv::Mat grey;
        cv::cvtColor(empty, grey, cv::COLOR_BGR2GRAY);  // (-215:Assertion failed) !_src.empty()
    });
    EXPECT_EQ(outcome.exit_code, stereo::cli::kExitUsageError);
    expect_one_error_line(outcome);
    EXPECT_NE(outcome.stderr_text.find("cvtColor"), std::string::npos) << outcome.stderr_text;
    EXPECT_EQ(outcome.stderr_text.find("OpenCV("), std::string::npos) << outcome.stderr_text;
    EXPECT_EQ(outcome.stderr_text.find(".cpp:"), std::string::npos) << outcome.stderr_text;
}

TEST(CliRun, OpenCvOutOfMemoryNamesTheLimit) {
    const Outcome outcome =
        run_command([] { CV_Error(cv::Error::StsNoMem, "Failed to allocate 40000000000 bytes"); });
    EXPECT_EQ(outcome.exit_code, stereo::cli::kExitUsageError);
    expect_one_error_line(outcome);
    EXPECT_NE(outcome.stderr_text.find("out of memory"), std::string::npos) << outcome.stderr_text;
    EXPECT_NE(outcome.stderr_text.find("--max-pixels"), std::string::npos) << outcome.stderr_text;
}

TEST(CliRun, BadAllocIsOneUsageLine) {
    const Outcome outcome = run_command([] { throw std::bad_alloc(); });
    EXPECT_EQ(outcome.exit_code, stereo::cli::kExitUsageError);
    expect_one_error_line(outcome);
    EXPECT_NE(outcome.stderr_text.find("out of memory"), std::string::npos) << outcome.stderr_text;
}

TEST(CliRun, DocumentedExceptionsKeepTheirCodes) {
    const Outcome usage = run_command([] { throw std::invalid_argument("bad\nnumber"); });
    EXPECT_EQ(usage.exit_code, stereo::cli::kExitUsageError);
    expect_one_error_line(usage);
    const Outcome io = run_command([] { throw std::runtime_error("cannot read 'x'"); });
    EXPECT_EQ(io.exit_code, stereo::cli::kExitIoError);
    expect_one_error_line(io);
    const Outcome mismatch = run_command([] { throw stereo::cli::MismatchError("3 pixels"); });
    EXPECT_EQ(mismatch.exit_code, stereo::cli::kExitMismatch);
    expect_one_error_line(mismatch);
}

}  // namespace
