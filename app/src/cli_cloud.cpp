// `stereo cloud DISP LEFT -o cloud.ply --focal F --baseline B | --calib FILE`: a coloured 3-D
// point cloud from a disparity map (stereo_io/point_cloud.hpp).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "cli_command.hpp"
#include "stereo_io/disparity_files.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/output.hpp"
#include "stereo_io/point_cloud.hpp"
#include "stereo_robot/calibration.hpp"

namespace stereo::cli {
namespace {

constexpr double kUnset = std::numeric_limits<double>::quiet_NaN();

struct CloudOptions {
    std::string disparity;
    std::string left;
    std::string output;
    std::string calib;
    double focal = kUnset;
    double baseline = kUnset;
    double cx = kUnset;
    double cy = kUnset;
    double doffs = 0.0;
    double scale = 1.0;
    bool png16 = false;
    bool binary = false;

    static constexpr std::string_view kName = "cloud";
    static constexpr std::string_view kDescription =
        "Write a coloured 3-D point cloud (PLY) from a disparity map.";
};

void run_cloud(const CloudOptions& options) {
    if (std::filesystem::path(options.output).extension() != ".ply") {
        throw std::invalid_argument("-o must name a .ply file, got '" + options.output + "'");
    }
    if (options.calib.empty() && (std::isnan(options.focal) || std::isnan(options.baseline))) {
        throw std::invalid_argument("give --focal and --baseline, or --calib");
    }
    io::check_outputs_distinct({options.output}, {options.disparity, options.left, options.calib});
    io::check_writable_location(options.output);
    io::CloudGeometry geometry{options.focal, options.baseline, options.cx, options.cy,
                               options.doffs};
    if (!options.calib.empty()) {
        const robot::StereoGeometry calib = robot::load_calibration(options.calib);
        geometry.focal = calib.focal_px;
        geometry.baseline = calib.baseline;
        if (std::isnan(options.cx)) {
            geometry.cx = calib.cx;
        }
        if (std::isnan(options.cy)) {
            geometry.cy = calib.cy;
        }
    }
    const auto encoding =
        io::encoding_of(options.disparity, options.png16 ? io::DisparityEncoding::offset16
                                                         : io::DisparityEncoding::scaled);
    const cv::Mat disparity = io::load_disparity_file(options.disparity, encoding, options.scale);
    const cv::Mat bgr = io::load_bgr(options.left);
    // The image centre when neither the options nor the calibration give the principal point.
    if (std::isnan(geometry.cx)) {
        geometry.cx = (bgr.cols - 1) / 2.0;
    }
    if (std::isnan(geometry.cy)) {
        geometry.cy = (bgr.rows - 1) / 2.0;
    }
    const auto points = io::disparity_to_points(disparity, bgr, geometry);
    io::write_file_atomic(options.output, io::encode_ply(points, options.binary));
    std::printf("%zu points (f %g, B %g, cx %g, cy %g, doffs %g)\n", points.size(), geometry.focal,
                geometry.baseline, geometry.cx, geometry.cy, geometry.doffs);
}

}  // namespace

void add_cloud_command(CLI::App& app) {
    const auto [command, options] = add_command<CloudOptions>(app, run_cloud);
    command
        ->add_option("DISP", options->disparity,
                     "Disparity: .pfm, or PNG (d * scale, 0 invalid; --png16: 32768 + 16 d)")
        ->required();
    command->add_option("LEFT", options->left, "The reference image, for the colours")->required();
    command->add_option("-o,--output", options->output, "Point cloud .ply")->required();
    auto* focal = command->add_option("--focal", options->focal, "Focal length, pixels");
    auto* baseline =
        command->add_option("--baseline", options->baseline, "Baseline (the cloud's unit)");
    command
        ->add_option("--calib", options->calib,
                     "KITTI calibration (P0/P1 lines): focal, baseline and principal point")
        ->excludes(focal)
        ->excludes(baseline);
    command->add_option("--cx", options->cx, "Principal point x, pixels (default: centre)");
    command->add_option("--cy", options->cy, "Principal point y, pixels (default: centre)");
    add_number_options(*command,
                       {{"--doffs", &options->doffs,
                         "Disparity offset: Z = f B / (d + doffs) (Middlebury 2014's doffs)"},
                        {"--scale", &options->scale, "PNG: stored value = d * scale",
                         checks::real_in(1e-3, 1e6)}});
    command->add_flag("--png16", options->png16, "PNG in offset16 form (stereo match --png16)");
    command->add_flag("--binary", options->binary, "binary_little_endian PLY instead of ASCII");
}

}  // namespace stereo::cli
