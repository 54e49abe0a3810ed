// The loops the references share: every cell of a volume, every pixel of a 3x3 neighbourhood.
// Written plainly, with no incremental tricks, like the references themselves.
#pragma once

#include "stereo/dsi.hpp"
#include "stereo/image.hpp"

namespace stereo::reference {

// visit(x, y, d) for every cell of a width x height x ndisp volume, plane by plane.
template <class Visit>
void for_each_cell(int width, int height, int ndisp, Visit visit) {
    for (int d = 0; d < ndisp; ++d) {
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                visit(x, y, d);
            }
        }
    }
}

// The cost volume of a per-pixel cost: cell (x, y, k) of an ndisp-plane volume holds
// pixel_cost(x, y, x - d), the left pixel (x, y) against the right pixel (x - d, y) with
// d = min_disp + k, or `outside` where that right pixel lies outside the image.
template <class PixelCost>
Dsi pixel_cost_volume(const Image& left, int ndisp, int min_disp, int outside,
                      PixelCost pixel_cost) {
    Dsi dsi(left.width, left.height, ndisp);
    for_each_cell(left.width, left.height, ndisp, [&](int x, int y, int k) {
        const int right_x = x - (min_disp + k);
        const bool inside = right_x >= 0 && right_x < left.width;
        dsi.at(x, y, k) = static_cast<Dsi::Value>(inside ? pixel_cost(x, y, right_x) : outside);
    });
    return dsi;
}

// visit(i, j) for the 3x3 offsets around a centre, the centre included.
template <class Visit>
void for_each_offset3x3(Visit visit) {
    for (int j = -1; j <= 1; ++j) {
        for (int i = -1; i <= 1; ++i) {
            visit(i, j);
        }
    }
}

}  // namespace stereo::reference
