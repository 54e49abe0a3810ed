// The subcommands of `stereo_experiments`: one file each, writing the tables or figures of one
// documentation page. Problems are reported by throwing (cli_run.hpp).
#pragma once

namespace CLI {
class App;
}

namespace stereo::experiments {

void add_hierarchical_eval_command(CLI::App& app);  // docs/results-hierarchical.md
void add_sigma_sweep_command(CLI::App& app);        // docs/sigma-sweep.md
void add_avoid_figures_command(CLI::App& app);      // docs/avoidance.md
void add_validation_eval_command(CLI::App& app);    // docs/results.md, validated output
void add_avoid_benchmark_command(CLI::App& app);    // docs/results-avoidance.md
void add_illumination_command(CLI::App& app);       // docs/results-illumination.md
void add_quad_eval_command(CLI::App& app);          // docs/results-quad.md

}  // namespace stereo::experiments
