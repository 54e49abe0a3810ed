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
// the error lines are prefixed with app's name.
int run(CLI::App& app, int argc, char** argv);

}  // namespace stereo::cli
