// `stereo distort SCENE OUT [options]`: write a decalibrated copy of a stereo scene folder
// (radial lens distortion of both images, vertical shift / rotation of the right image) for the
// evaluation of the hierarchical search (docs/results-hierarchical.md).
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "cli.hpp"
#include "cli_command.hpp"
#include "stereo_io/distortion.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/output.hpp"

namespace stereo::cli {

namespace {
namespace fs = std::filesystem;

struct DistortOptions {
    std::string scene;
    std::string output;
    io::PairWarp warp{10.0, 0.0, 0.0};
    double gt_scale = 1.0;
    std::string gt_mode = "warped";  // or "exact"

    static constexpr std::string_view kName = "distort";
    static constexpr std::string_view kDescription =
        "Write a decalibrated copy of a scene folder (lens distortion, shift, rotation).";
};

void check_size(const cv::Mat& mat, const cv::Mat& left, const fs::path& path) {
    if (mat.size() != left.size()) {
        throw std::invalid_argument("\"" + path.string() + "\" is " + std::to_string(mat.cols) +
                                    "x" + std::to_string(mat.rows) + " but the left image is " +
                                    std::to_string(left.cols) + "x" + std::to_string(left.rows));
    }
}

void run_distort(const DistortOptions& options) {
    const fs::path scene(options.scene);
    const fs::path out(options.output);
    std::error_code error;
    if (!fs::is_directory(scene, error)) {
        throw std::runtime_error("scene folder \"" + options.scene + "\" does not exist");
    }
    io::check_output_folder(out);
    // Writing into the scene itself (or a folder inside it, or over a file a link in the scene
    // points at) would replace the inputs with their distorted copies.
    std::vector<fs::path> outputs;
    for (const char* name :
         {"left.png", "right.png", "gt.png", "nonocc.png", "all.png", "disc.png"}) {
        outputs.push_back(out / name);
    }
    io::check_outputs(outputs, {.folders = {scene}});
    if (fs::is_directory(out, error)) {
        for (const fs::path& output : outputs) {
            io::check_writable_location(output);
        }
    }
    const cv::Mat left = io::load_bgr(scene / "left.png");
    const cv::Mat right = io::load_bgr(scene / "right.png");
    check_size(right, left, scene / "right.png");
    const io::PairTransform transform(left.cols, left.rows, options.warp);  // checks the warp

    // Everything is computed and encoded in memory before the first file is written.
    std::vector<std::pair<std::string, cv::Mat>> files = {
        {"left.png", io::warp_left(left, transform, cv::INTER_LINEAR)},
        {"right.png", io::warp_right(right, transform, cv::INTER_LINEAR)}};
    if (fs::exists(scene / "gt.png")) {
        const cv::Mat gt = io::load_disparity(scene / "gt.png", options.gt_scale);
        check_size(gt, left, scene / "gt.png");
        const cv::Mat warped = options.gt_mode == "exact" ? io::exact_ground_truth(gt, transform)
                                                          : io::warp_ground_truth(gt, transform);
        cv::Mat stored;
        warped.convertTo(stored, CV_16UC1, options.gt_scale);  // rounds to 1/scale
        double max = 0;
        cv::minMaxLoc(stored, nullptr, &max);
        if (max <= 255) {  // 8-bit like the input whenever the values allow it
            stored.convertTo(stored, CV_8UC1);
        }
        files.emplace_back("gt.png", stored);
    }
    for (const char* mask : {"nonocc.png", "all.png", "disc.png"}) {
        if (fs::exists(scene / mask)) {
            const cv::Mat loaded = io::load_mask(scene / mask);
            check_size(loaded, left, scene / mask);
            files.emplace_back(mask, io::warp_left(loaded, transform, cv::INTER_NEAREST));
        }
    }
    fs::create_directories(out);
    std::vector<std::pair<fs::path, cv::Mat>> paths;
    for (const auto& [name, mat] : files) {
        paths.emplace_back(out / name, mat);
    }
    io::write_pngs(paths);  // all or nothing
    std::cout << "wrote " << files.size() << " files to " << options.output << " (distortion "
              << options.warp.distortion_percent << " %, right shift " << options.warp.right_shift_y
              << " px, right rotation " << options.warp.right_rotation_deg << " deg, gt "
              << options.gt_mode << ")\n";
}

}  // namespace

void add_distort_command(CLI::App& app) {
    const auto [command, options] = add_command<DistortOptions>(app, run_distort);
    command->add_option("SCENE", options->scene, "Folder with left.png, right.png [gt.png, masks]")
        ->required();
    command->add_option("OUT", options->output, "Output folder (created if its parent exists)")
        ->required();
    add_number_options(
        *command,
        {{"--distortion", &options->warp.distortion_percent,
          "Radial distortion P % of both images (> 0 barrel, < 0 pincushion)"},
         {"--shift-y", &options->warp.right_shift_y, "Move the right image down by S pixels"},
         {"--rotate", &options->warp.right_rotation_deg,
          "Rotate the right image by DEG degrees (counter-clockwise) about its centre"},
         {"--gt-scale", &options->gt_scale, "gt.png holds disparity * G", disparity_scale()}});
    command
        ->add_option("--gt", options->gt_mode,
                     "warped: distort the GT like the left image (the thesis); exact: follow "
                     "every pixel through the warp")
        ->check(CLI::IsMember({"warped", "exact"}))
        ->capture_default_str();
}

}  // namespace stereo::cli
