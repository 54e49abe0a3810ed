// Stereo front end of the SLAM layer (thesis Sec. 4.2.1): the model's sparse matcher
// (stereo/sparse.hpp, method "sparse" of the matcher registry) with the SLAM layer's parameters.
// Thresholds: docs/slam.md.
#pragma once

#include <string>

#include "stereo/image.hpp"
#include "stereo/sparse.hpp"

namespace stereo::robot::slam {

using sparse::kNoDisparity;
using sparse::SparseDisparity;
using sparse::ValidationCounts;

struct FrontendParams {
    int ndisp = 64;           // disparity labels 0 .. ndisp-1
    int window = 11;          // aggregation window (the model's default)
    double sigma = 3.0;       // aggregation Gaussian sigma (the model's default)
    int uniqueness = 10;      // stage 6's ratio U: (C2 - C1) / C1 must be larger than U / 100
    int lr_tolerance = 1;     // |dL - dR| <= this
    std::string cost = "ad";  // the matching cost (stereo::cost_names(); docs/slam.md)
};

// The registry's "sparse" matcher on a pair. Throws std::invalid_argument for impossible
// parameters.
SparseDisparity sparse_disparity(const Image& left, const Image& right,
                                 const FrontendParams& params, ValidationCounts* counts = nullptr);

// Throws std::invalid_argument unless the parameters fit an image of this size.
void validate_frontend(const FrontendParams& params, int width, int height);

}  // namespace stereo::robot::slam
