// The subcommands of `stereo_experiments`: one file each, writing the tables or figures of one
// documentation page. Problems are reported by throwing (cli_run.hpp).
#pragma once

#include <filesystem>
#include <vector>

#include "stereo_io/middlebury.hpp"

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
void add_asw_eval_command(CLI::App& app);           // docs/results-asw-tables.md

// Every scene with ground truth under `root` that is present: the four Middlebury 2003 pairs
// (with their masks), Reindeer (2005), Cloth3 and Wood2 (2006) at half size, and Aloe at half
// size (no masks). Absent scenes are skipped; present but broken ones throw.
std::vector<io::SceneData> load_ground_truth_scenes(const std::filesystem::path& root);

}  // namespace stereo::experiments
