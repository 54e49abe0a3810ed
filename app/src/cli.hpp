// The subcommands of the `stereo` tool. Each file cli_<name>.cpp adds one subcommand to the
// application; its callback does the work and reports problems by throwing. cli::run()
// (cli_run.hpp) turns every exception into a single "stereo: error: ..." line and an exit code.
#pragma once

#include "cli_run.hpp"

namespace CLI {
class App;
}

namespace stereo::cli {

void add_match_command(CLI::App& app);
void add_eval_command(CLI::App& app);
void add_middlebury_command(CLI::App& app);
void add_cosim_command(CLI::App& app);
void add_fis_command(CLI::App& app);
void add_avoid_command(CLI::App& app);
void add_distort_command(CLI::App& app);
void add_relight_command(CLI::App& app);
void add_slam_command(CLI::App& app);
void add_quad_command(CLI::App& app);
void add_cloud_command(CLI::App& app);
void add_board_command(CLI::App& app);
void add_vectors_command(CLI::App& app);

// All of the above, with one subcommand required: the whole `stereo` application.
void add_stereo_commands(CLI::App& app);

}  // namespace stereo::cli
