// Writes the tiny stereo sequences the `stereo slam` command-line tests run on, into the folder
// given as the only argument: one good KITTI-layout sequence and one broken copy per error.
// Deterministic (fixed seed).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

#include "fixture_main.hpp"
#include "stereo_io/io.hpp"

namespace {

namespace fs = std::filesystem;
namespace io = stereo::io;

constexpr int kWidth = 96;
constexpr int kHeight = 48;
constexpr int kFrames = 3;
constexpr int kShift = 4;  // disparity of every pixel

const char* kCalib =
    "P0: 100 0 48 0 0 100 24 0 0 0 1 0\n"
    "P1: 100 0 48 -50 0 100 24 0 0 0 1 0\n";
const char* kIdentity = "1 0 0 0 0 1 0 0 0 0 1 0\n";

std::string frame_name(int i) {
    char name[16];
    std::snprintf(name, sizeof name, "%06d.png", i);
    return name;
}

// Random texture; the right image is the left one shifted by kShift, the scene moves 2 px to
// the left from frame to frame.
void make_sequence(const fs::path& dir, int left_frames, int right_frames, std::mt19937& rng) {
    fs::create_directories(dir / "image_l");
    fs::create_directories(dir / "image_r");
    cv::Mat world(kHeight, kWidth + 2 * kFrames + kShift, CV_8UC1);
    cv::randu(world, 0, 256);
    (void)rng;
    for (int i = 0; i < std::max(left_frames, right_frames); ++i) {
        const cv::Mat left = world(cv::Rect(2 * i + kShift, 0, kWidth, kHeight)).clone();
        const cv::Mat right = world(cv::Rect(2 * i, 0, kWidth, kHeight)).clone();
        if (i < left_frames) {
            io::write_png(dir / "image_l" / frame_name(i), left);
        }
        if (i < right_frames) {
            io::write_png(dir / "image_r" / frame_name(i), right);
        }
    }
    std::ofstream(dir / "calib.txt") << kCalib;
}

void write_fixtures(const fs::path& dir) {
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::mt19937 rng(20240612U);
    cv::setRNGSeed(20240612);

    make_sequence(dir / "ok", kFrames, kFrames, rng);
    std::ofstream(dir / "ok" / "poses.txt") << kIdentity << kIdentity << kIdentity;

    make_sequence(dir / "no_poses", kFrames, kFrames, rng);
    make_sequence(dir / "unequal", kFrames, kFrames - 1, rng);
    make_sequence(dir / "bad_calib", kFrames, kFrames, rng);
    std::ofstream(dir / "bad_calib" / "calib.txt") << "P0: 1 2 3\nnot a calibration\n";
    // Issue 50: both projection matrices with the same translation, i.e. no baseline.
    make_sequence(dir / "no_baseline", kFrames, kFrames, rng);
    std::ofstream(dir / "no_baseline" / "calib.txt")
        << "P0: 100 0 48 0 0 100 24 0 0 0 1 0\nP1: 100 0 48 0 0 100 24 0 0 0 1 0\n";
    make_sequence(dir / "no_calib", kFrames, kFrames, rng);
    fs::remove(dir / "no_calib" / "calib.txt");
    make_sequence(dir / "no_right", kFrames, kFrames, rng);
    fs::remove_all(dir / "no_right" / "image_r");
    make_sequence(dir / "bad_poses", kFrames, kFrames, rng);
    std::ofstream(dir / "bad_poses" / "poses.txt") << kIdentity << kIdentity;
    make_sequence(dir / "corrupt_right", kFrames, kFrames, rng);
    std::ofstream(dir / "corrupt_right" / "image_r" / frame_name(kFrames - 1)) << "not a PNG\n";
    make_sequence(dir / "odd_size", kFrames, kFrames, rng);
    io::write_png(dir / "odd_size" / "image_r" / frame_name(1),
                  cv::Mat(kHeight, kWidth - 8, CV_8UC1));
}

}  // namespace

int main(int argc, char** argv) {
    return stereo::test::fixture_main(argc, argv, "make_slam_fixtures", write_fixtures);
}
