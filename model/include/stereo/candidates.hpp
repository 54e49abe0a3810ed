// The candidate displacements of every pixel and their tie order: what the plane scheduler
// (stereo/search.hpp) visits and the winner-takes-all stage (stereo/stages/wta.hpp) ranks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace stereo {

// The candidates of every pixel: cols x rows displacements; candidate (i, j) of pixel p is the
// left pixel (x, y) against the right pixel (x - d, y + v), d = base_d[p] + i, v = base_v[p] + j.
// Among equal costs the candidate closest to (prefer_d, prefer_v) wins, vertically first, then
// the smaller v, then the smaller d. A uniform grid holds one value in each vector, shared by
// every pixel.
struct CandidateGrid {
    int width = 0;
    int height = 0;
    int cols = 0;
    int rows = 0;
    std::vector<std::int16_t> base_d;
    std::vector<std::int16_t> base_v;
    std::vector<std::int16_t> prefer_d;
    std::vector<std::int16_t> prefer_v;

    // The 1-D search: d = min_disp .. min_disp + ndisp - 1, v = 0, ties to the smaller d.
    static CandidateGrid horizontal(int width, int height, int ndisp, int min_disp = 0);
    bool uniform() const { return base_d.size() == 1; }
    std::size_t at(std::size_t p) const { return uniform() ? 0 : p; }
};

// Tie key of candidate (d, v) for a pixel preferring (prefer_d, prefer_v): smaller wins.
std::int64_t tie_key(int d, int v, int prefer_d, int prefer_v);

}  // namespace stereo
