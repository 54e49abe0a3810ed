// Every subcommand of `stereo`, in one place: main() and the CLI fuzz harness
// (fuzz/fuzz_cli_options.cpp) build the same application from it.
#include <string>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "stereo/version.hpp"

namespace stereo::cli {

void add_stereo_commands(CLI::App& app) {
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string("stereo ") + kVersion,
                         "Print the version (also the \"version\" field of every JSON output)");
    add_match_command(app);
    add_eval_command(app);
    add_middlebury_command(app);
    add_cosim_command(app);
    add_fis_command(app);
    add_avoid_command(app);
    add_distort_command(app);
    add_relight_command(app);
    add_slam_command(app);
    add_quad_command(app);
    add_cloud_command(app);
    add_board_command(app);
    add_vectors_command(app);
}

}  // namespace stereo::cli
