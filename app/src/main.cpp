// `stereo`: command-line front end of the golden model. See cli.hpp for the structure.
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>
#include <opencv2/core/utils/logger.hpp>

#include "cli.hpp"

namespace {

// Every failure is exactly one line on stderr, so scripts can rely on it.
int fail(std::string message, int exit_code) {
    for (char& c : message) {
        if (c == '\n' || c == '\r') {
            c = ' ';
        }
    }
    while (!message.empty() && message.back() == ' ') {
        message.pop_back();
    }
    std::cerr << "stereo: error: " << message << '\n';
    return exit_code;
}

}  // namespace

int main(int argc, char** argv) {
    // Our own messages name the file and the problem; OpenCV's log lines would only add noise.
    cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);

    CLI::App app{"Stereo matching with the bit-exact golden model, and its evaluation.", "stereo"};
    app.require_subcommand(1);
    stereo::cli::add_match_command(app);
    stereo::cli::add_eval_command(app);
    stereo::cli::add_middlebury_command(app);
    stereo::cli::add_cosim_command(app);
    stereo::cli::add_fis_command(app);
    stereo::cli::add_avoid_command(app);
    stereo::cli::add_distort_command(app);
    stereo::cli::add_hierarchical_eval_command(app);
    stereo::cli::add_slam_command(app);

    try {
        app.parse(argc, argv);  // runs the chosen subcommand's callback
        return stereo::cli::kExitOk;
    } catch (const CLI::Success& help) {
        return app.exit(help);  // --help: usage on stdout, exit 0
    } catch (const CLI::ParseError& error) {
        return fail(std::string(error.what()) + " (run with --help for usage)",
                    stereo::cli::kExitUsageError);
    } catch (const stereo::cli::MismatchError& error) {
        return fail(error.what(), stereo::cli::kExitMismatch);
    } catch (const std::invalid_argument& error) {
        return fail(error.what(), stereo::cli::kExitUsageError);
    } catch (const std::exception& error) {
        return fail(error.what(), stereo::cli::kExitIoError);
    } catch (...) {
        return fail("unexpected internal error", stereo::cli::kExitIoError);
    }
}
