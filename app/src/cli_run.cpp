#include "cli_run.hpp"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>

#include <fcntl.h>
#include <unistd.h>

#include <new>

#include <CLI/CLI.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/utils/logger.hpp>

#include "cli_checks.hpp"
#include "stereo_io/limits.hpp"
#include "stereo_io/output.hpp"

namespace stereo::cli {
namespace {

// Every failure is exactly one line on stderr, so scripts can rely on it.
int fail(const std::string& program, std::string message, int exit_code) {
    for (char& c : message) {
        if (c == '\n' || c == '\r') {
            c = ' ';
        }
    }
    while (!message.empty() && message.back() == ' ') {
        message.pop_back();
    }
    std::cerr << program << ": error: " << message << '\n';
    return exit_code;
}

// OpenCV's exceptions carry a multi-line what() ("OpenCV(4.6.0) file:line: error: (-215:Assertion
// failed) ... in function '...'"): reported as one line without the source location. They come
// from inputs OpenCV cannot handle (sizes, depths, memory), so they are usage errors.
std::string opencv_message(const cv::Exception& error) {
    std::string what = error.err.empty() ? std::string("unknown error") : error.err;
    if (error.code == cv::Error::StsNoMem) {
        return "out of memory in OpenCV (" + what +
               "): the input is too large for this machine (see --max-pixels)";
    }
    std::string message = "OpenCV cannot process the input";
    if (!error.func.empty()) {
        message += " (" + error.func + ")";
    }
    return message + ": " + what;
}

// Descriptors 0, 1 and 2 that are closed get /dev/null as a stand-in, so that no file the
// command opens becomes its standard output or error (a temporary on descriptor 2 would receive
// libpng's messages). Returns whether standard output was closed: every command prints a result
// there, so that is an error before any work.
bool reserve_standard_descriptors() {
    bool stdout_closed = false;
    for (const int descriptor : {STDIN_FILENO, STDOUT_FILENO, STDERR_FILENO}) {
        if (::fcntl(descriptor, F_GETFD) != -1 || errno != EBADF) {
            continue;
        }
        stdout_closed = stdout_closed || descriptor == STDOUT_FILENO;
        const int opened = ::open("/dev/null", descriptor == STDIN_FILENO ? O_RDONLY : O_WRONLY);
        if (opened >= 0 && opened != descriptor) {
            ::dup2(opened, descriptor);
            ::close(opened);
        }
    }
    return stdout_closed;
}

// Why what was printed did not all reach standard output (/dev/full, a pipe nobody reads);
// empty when it did.
std::string stdout_failure() {
    errno = 0;
    std::cout.flush();
    int error = errno;
    if (std::fflush(stdout) != 0) {
        error = errno;
    }
    if (std::ferror(stdout) == 0 && std::cout.good()) {
        return {};
    }
    const std::string message = "cannot write the standard output";
    return error != 0 ? message + ": " + std::strerror(error) : message;
}

int run_command(CLI::App& app, int argc, char** argv, const std::string& program) {
    app.add_option("--max-pixels",
                   "Largest image any input may declare, in pixels (default 2^26, "
                   "or STEREO_MAX_IMAGE_PIXELS)")
        ->check(checks::integer_in(1, std::int64_t{1} << 34))
        ->each([](const std::string& value) { io::set_max_image_pixels(std::stoll(value)); });
    checks::plain_numbers(app);  // decimal integers, finite real numbers, in every subcommand
    for (CLI::App* command : app.get_subcommands({})) {
        command->fallthrough();  // also after the subcommand: `stereo match ... --max-pixels N`
    }
    try {
        app.parse(argc, argv);  // runs the chosen subcommand's callback
        return kExitOk;
    } catch (const CLI::Success& help) {
        return app.exit(help);  // --help: usage on stdout, exit 0
    } catch (const CLI::ParseError& error) {
        return fail(program, std::string(error.what()) + " (run with --help for usage)",
                    kExitUsageError);
    } catch (const MismatchError& error) {
        return fail(program, error.what(), kExitMismatch);
    } catch (const std::invalid_argument& error) {
        return fail(program, error.what(), kExitUsageError);
    } catch (const cv::Exception& error) {
        return fail(program, opencv_message(error), kExitUsageError);
    } catch (const std::bad_alloc&) {
        return fail(program,
                    "out of memory: the input is too large for this machine (see --max-pixels)",
                    kExitUsageError);
    } catch (const std::exception& error) {
        return fail(program, error.what(), kExitIoError);
    } catch (...) {
        return fail(program, "unexpected internal error", kExitIoError);
    }
}

}  // namespace

void check_stdout() {
    const std::string failure = stdout_failure();
    if (!failure.empty()) {
        throw std::runtime_error(failure);
    }
}

int run(CLI::App& app, int argc, char** argv) {
    // Our own messages name the file and the problem; OpenCV's log lines would only add noise.
    cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
    const std::string program = app.get_name();
    if (reserve_standard_descriptors()) {
        return fail(program, "cannot write the standard output: it is closed", kExitIoError);
    }
    // Temporaries removed on signals, SIGPIPE and SIGXFSZ turned into write errors, no output
    // over a file the command read (stereo_io/output.hpp).
    io::install_process_guards(program);
    const int status = run_command(app, argc, argv, program);
    // What could not be printed is an error, reported once: a command that failed already said
    // why (and printed nothing on stdout).
    const std::string failure = stdout_failure();
    if (status == kExitOk && !failure.empty()) {
        return fail(program, failure, kExitIoError);
    }
    return status;
}

}  // namespace stereo::cli
