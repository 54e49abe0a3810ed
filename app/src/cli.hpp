// The subcommands of the `stereo` tool. Each file cli_<name>.cpp adds one subcommand to the
// application; its callback does the work and reports problems by throwing. main() turns every
// exception into a single "stereo: error: ..." line and one of the exit codes below.
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

void add_match_command(CLI::App& app);
void add_eval_command(CLI::App& app);
void add_middlebury_command(CLI::App& app);
void add_cosim_command(CLI::App& app);
void add_fis_command(CLI::App& app);
void add_avoid_command(CLI::App& app);
void add_distort_command(CLI::App& app);
void add_hierarchical_eval_command(CLI::App& app);
void add_slam_command(CLI::App& app);

}  // namespace stereo::cli
