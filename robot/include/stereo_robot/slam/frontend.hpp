// Stereo front end of the SLAM layer (thesis Sec. 4.2.1): the model's sparse matcher
// (stereo/sparse.hpp, method "sparse" of the matcher registry: the pipeline without CA, every
// stage-6 check) with the SLAM layer's parameters, computed by the fast CPU engine
// (stereo/fast_engine.hpp), bit for bit the model's. Thresholds: docs/slam.md.
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
    bool operator==(const FrontendParams&) const = default;
};

// The registry's "sparse" matcher on a pair, on `threads` worker threads of the fast engine
// (1: the calling thread). Each calling thread keeps one engine for the last parameters and
// thread count, so a sequence reuses its buffers. Throws std::invalid_argument for impossible
// parameters.
SparseDisparity sparse_disparity(const Image& left, const Image& right,
                                 const FrontendParams& params, ValidationCounts* counts = nullptr,
                                 int threads = 1);

// The same through the registry's model engine ("sparse", "model"): the reference the fast
// front end is tested against.
SparseDisparity sparse_disparity_model(const Image& left, const Image& right,
                                       const FrontendParams& params,
                                       ValidationCounts* counts = nullptr);

// Throws std::invalid_argument unless the parameters fit an image of this size.
void validate_frontend(const FrontendParams& params, int width, int height);

}  // namespace stereo::robot::slam
