// `stereo`: command-line front end of the golden model. See cli.hpp for the structure.
#include <CLI/CLI.hpp>

#include "cli.hpp"

int main(int argc, char** argv) {
    CLI::App app{"Stereo matching with the bit-exact golden model, and its evaluation.", "stereo"};
    app.require_subcommand(1);
    stereo::cli::add_match_command(app);
    stereo::cli::add_eval_command(app);
    stereo::cli::add_middlebury_command(app);
    stereo::cli::add_cosim_command(app);
    stereo::cli::add_fis_command(app);
    stereo::cli::add_avoid_command(app);
    stereo::cli::add_distort_command(app);
    stereo::cli::add_relight_command(app);
    stereo::cli::add_slam_command(app);
    return stereo::cli::run(app, argc, argv);
}
