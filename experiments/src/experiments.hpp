// The subcommands of `stereo_experiments`: one file each, writing the tables or figures of one
// documentation page. Problems are reported by throwing (cli_run.hpp).
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "stereo/pipeline.hpp"
#include "stereo/validated.hpp"
#include "stereo_io/middlebury.hpp"

namespace CLI {
class App;
}

namespace stereo::experiments {

void add_hierarchical_eval_command(CLI::App& app);       // docs/results-hierarchical.md
void add_hierarchical_validated_command(CLI::App& app);  // docs/results-hierarchical.md
void add_sigma_sweep_command(CLI::App& app);             // docs/sigma-sweep.md
void add_avoid_figures_command(CLI::App& app);           // docs/avoidance.md
void add_validation_eval_command(CLI::App& app);         // docs/results.md, validated output
void add_avoid_benchmark_command(CLI::App& app);         // docs/results-avoidance.md
void add_illumination_command(CLI::App& app);            // docs/results-illumination.md
void add_quad_eval_command(CLI::App& app);               // docs/results-quad.md
void add_asw_eval_command(CLI::App& app);                // docs/results-asw-tables.md
void add_subpixel_calibration_command(CLI::App& app);    // docs/fixed-point.md, stage 6
void add_slam_scale_command(CLI::App& app);              // docs/results-slam.md, issue 50

// The Middlebury 2003 pairs under `root` that are present (with their masks), in the order of
// io::middlebury2003_scenes(); absent ones are skipped, present but broken ones throw.
std::vector<io::SceneData> load_2003_scenes(const std::filesystem::path& root);

// A number with `digits` decimals, as the generated tables print them.
std::string fmt(double value, int digits = 2);

// Every scene with ground truth under `root` that is present: the four Middlebury 2003 pairs
// (with their masks), Reindeer (2005), Cloth3 and Wood2 (2006) at half size, and Aloe at half
// size (no masks). Absent scenes are skipped; present but broken ones throw.
std::vector<io::SceneData> load_ground_truth_scenes(const std::filesystem::path& root);

// `stereo match`'s validated output for params.cost: stage 6 with every step on at that cost's
// uniqueness ratio and left-right tolerance (stereo/defaults.hpp), then the speckle filter at its
// defaults; params.validation is replaced.
ValidatedDisparity match_as_stereo_match(const Image& left, const Image& right, MatchParams params);

// Files a subcommand writes together with io::write_files_atomic (all or nothing).
using OutputFiles = std::vector<std::pair<std::filesystem::path, std::string>>;

// Appends the report files a subcommand was asked for: `markdown` to markdown_path and the
// versioned `report` (io::versioned, indented) to json_path; an empty path is not written.
void add_report_files(OutputFiles& files, const std::string& markdown_path,
                      const std::string& markdown, const std::string& json_path,
                      const nlohmann::json& report);

// Writes `files` followed by the report files (add_report_files) all or nothing
// (io::write_files_atomic), then prints `markdown` on stdout.
void print_and_write_report(OutputFiles files, const std::string& markdown_path,
                            const std::string& markdown, const std::string& json_path,
                            const nlohmann::json& report);

// Before any work: the output files (empty = not asked for) must be distinct and creatable
// (io::check_outputs, io::check_writable_location) and each figure folder must exist, so a run of
// many minutes does not end in an unwritable path; neither may lie inside `data_dir`, the folder
// the generator reads (empty: none).
void check_report_outputs(const std::vector<std::string>& files,
                          const std::vector<std::string>& folders = {},
                          const std::string& data_dir = {});

}  // namespace stereo::experiments
