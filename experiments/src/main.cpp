// `stereo_experiments`: the result generators behind docs/ (see experiments.hpp).
#include <CLI/CLI.hpp>

#include "cli_run.hpp"
#include "experiments.hpp"

int main(int argc, char** argv) {
    CLI::App app{"Result generators: the tables and figures of the documentation.",
                 "stereo_experiments"};
    app.require_subcommand(1);
    stereo::experiments::add_hierarchical_eval_command(app);
    stereo::experiments::add_hierarchical_validated_command(app);
    stereo::experiments::add_sigma_sweep_command(app);
    stereo::experiments::add_avoid_figures_command(app);
    stereo::experiments::add_validation_eval_command(app);
    stereo::experiments::add_avoid_benchmark_command(app);
    stereo::experiments::add_illumination_command(app);
    stereo::experiments::add_quad_eval_command(app);
    stereo::experiments::add_asw_eval_command(app);
    stereo::experiments::add_subpixel_calibration_command(app);
    stereo::experiments::add_slam_scale_command(app);
    return stereo::cli::run(app, argc, argv);
}
