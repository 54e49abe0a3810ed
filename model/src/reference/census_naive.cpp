// Naive reference of the census cost (stereo/stages/census.hpp): the code of each pixel is
// rebuilt for every comparison and the differing bits are counted one at a time.
#include "cells.hpp"
#include "stereo/edge_frontend.hpp"
#include "stereo/reference.hpp"
#include "stereo/stages/census.hpp"

namespace stereo::census::naive {
namespace {

// Bit n of the code of (x, y): the n-th neighbour in raster order (centre skipped) is darker.
bool bit(const Image& grey, int x, int y, int n) {
    const int k = n < kBits / 2 ? n : n + 1;  // skip the centre
    const int nx = x + k % (2 * kRadius + 1) - kRadius;
    const int ny = y + k / (2 * kRadius + 1) - kRadius;
    if (nx < 0 || ny < 0 || nx >= grey.width || ny >= grey.height) {
        return false;
    }
    return grey.at(nx, ny, 0) < grey.at(x, y, 0);
}

}  // namespace

int pixel_cost(const Image& left_grey, int x, int y, const Image& right_grey, int xr, int yr) {
    int distance = 0;
    for (int n = 0; n < kBits; ++n) {
        distance += bit(left_grey, x, y, n) != bit(right_grey, xr, yr, n) ? 1 : 0;
    }
    return distance * kWeight;
}

Dsi cost(const Image& left, const Image& right, int ndisp, int min_disp) {
    check_pair(left, right);
    const Image l = edge_frontend::naive::luma(left);
    const Image r = edge_frontend::naive::luma(right);
    return reference::pixel_cost_volume(
        left, ndisp, min_disp, fx::kCostOutside,
        [&](int x, int y, int right_x) { return pixel_cost(l, x, y, r, right_x, y); });
}

}  // namespace stereo::census::naive
