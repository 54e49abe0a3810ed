// The error and exit-code convention every executable of the tool shares (`stereo`,
// `stereo_experiments`): a command reports a problem by throwing, and run() turns every exception
// into exactly one "<program>: error: ..." line on stderr and one of the exit codes below.
#pragma once

#include <stdexcept>

namespace CLI {
class App;
}

namespace stereo::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitIoError = 1;     // missing, unreadable or unwritable files
inline constexpr int kExitUsageError = 2;  // bad options, parameters or mismatched inputs
inline constexpr int kExitMismatch = 3;    // cosim: the RTL differs from the golden model

// Thrown when a check of results fails (not a usage or I/O problem).
class MismatchError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Parses the command line, runs the chosen subcommand's callback and returns the exit code;
// the error lines are prefixed with app's name. Before parsing it installs the output layer's
// process guards (io::install_process_guards: temporaries removed on signals, SIGPIPE and
// SIGXFSZ ignored so that their writes fail and are reported) and gives closed standard
// descriptors a stand-in (a closed standard output is an error at once: every command prints
// there); after the command it flushes standard output, and a write that failed there
// (/dev/full, a pipe nobody reads) turns a success into exit 1 with one error line.
int run(CLI::App& app, int argc, char** argv);

// Throws std::runtime_error when something printed on standard output could not be written: a
// command that streams (avoid on a sequence) calls it after each line, so that it stops at the
// first line nobody receives instead of at the end.
void check_stdout();

}  // namespace stereo::cli
