// The plane scheduler: one loop that runs a composition of stages (stereo/stages.hpp) over a grid
// of candidate displacements. The 1-D pipeline (candidates d = 0..N-1), the hierarchical levels
// (2-D grids) and the edge front end are all this loop with different stages and grids.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "stereo/candidates.hpp"
#include "stereo/stages.hpp"
#include "stereo/stages/wta.hpp"

namespace stereo {

// Which neighbouring candidates the first refiner reads (CA rule 1's "d-1 / d+1").
enum class CaNeighbours {
    horizontal,               // (i-1, j) and (i+1, j): the 1-D rule, row by row (default)
    horizontal_and_vertical,  // also (i, j-1) and (i, j+1)
};

struct SearchStages {
    const CostFunction& cost;
    Aggregator& aggregator;
    std::span<Refiner* const> refiners;  // applied in order to every aggregated plane
    Selector& selector;
    CaNeighbours neighbours = CaNeighbours::horizontal;
};

// Streams the candidates in order k = j * cols + i: cost plane, aggregation, refiners, selector.
// Only the aggregated planes the first refiner still needs are kept (3 for a horizontal
// neighbourhood, 2 cols + 1 with vertical neighbours). Returns the DSI cells computed.
std::int64_t search(const PlanarImage& left, const PlanarImage& right, const CandidateGrid& grid,
                    const SearchStages& stages);

// Cost plane of candidate (i, j): stage 1 with fx::kCostOutside outside the right image.
void cost_plane(const CostFunction& cost, const PlanarImage& left, const PlanarImage& right,
                const CandidateGrid& grid, int i, int j, CostValue* out);

// Stage 1 over a whole 1-D volume (plane k: d = min_disp + k), for the stage-by-stage tests.
Dsi cost_volume(const CostFunction& cost, const Image& left, const Image& right, int ndisp,
                int min_disp = 0);

// A pixel is valid when its window and CA neighbourhood (`reach`) lie inside both images at its
// displacement: reach <= x < W - reach, reach <= y < H - reach, x - d >= reach and
// reach <= y + v < H - reach.
bool window_valid(int x, int y, int d, int v, int width, int height, int reach);

}  // namespace stereo
