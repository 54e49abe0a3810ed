// Row-band parallelism for the stereo front ends (issue 20): the image pair is cut into
// horizontal bands, each band is matched with `halo` extra rows above and below by the golden
// model itself on its own thread, and the band's own rows are stitched together. Every output
// pixel of the matchers used here depends only on input rows within a fixed vertical radius
// (LoG + Laplacian + zero crossings + aggregation window for the edge front end; aggregation
// window for the sparse one; the invalid border is decided from the window alone), so with a
// halo at least that radius the result equals the single-threaded one bit for bit
// (tests/test_bands.cpp checks it). Nothing of the model is re-implemented.
#pragma once

#include <functional>

#include "stereo/edge_frontend.hpp"
#include "stereo/image.hpp"
#include "stereo_robot/slam/frontend.hpp"

namespace stereo::robot {

// Rows [first, last) of `image`, copied.
Image rows_of(const Image& image, int first, int last);

// The vertical reach of the edge front end: LoG radius + 1 (Laplacian) + 1 (zero crossing
// below) + aggregation radius.
int edge_frontend_reach(const MatchParams& params, const edge_frontend::EdgeParams& edges);

// edge_frontend::match on `threads` bands (threads <= 1, or too few rows: one call).
DisparityMap edge_match_bands(const Image& left, const Image& right, const MatchParams& params,
                              const edge_frontend::EdgeParams& edges, int threads);

// slam::sparse_disparity on `threads` worker threads of the fast engine (its own row tiles).
slam::SparseDisparity sparse_disparity_bands(const Image& left, const Image& right,
                                             const slam::FrontendParams& params, int threads);

// Threads to use when the user gives 0: std::thread::hardware_concurrency(), at least 1.
int default_threads();

}  // namespace stereo::robot
