// The plane scheduler: one loop that runs a composition of stages (stereo/stages.hpp) over a grid
// of candidate displacements. The 1-D pipeline (candidates d = 0..N-1), the hierarchical levels
// (2-D grids) and the edge front end are all this loop with different stages and grids.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "stereo/stages.hpp"

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

// Which neighbouring candidates the first refiner reads (CA rule 1's "d-1 / d+1").
enum class CaNeighbours {
    horizontal,               // (i-1, j) and (i+1, j): the 1-D rule, row by row (default)
    horizontal_and_vertical,  // also (i, j-1) and (i, j+1)
};

// The winner of every pixel: displacement (d, v), valid or not.
struct Winners {
    int width = 0;
    int height = 0;
    std::vector<std::int16_t> disparity;
    std::vector<std::int16_t> vertical;
    std::vector<std::uint8_t> valid;  // filled by the caller's border rule

    std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width + x; }
    bool operator==(const Winners&) const = default;
};

// The model's selector: winner takes all over the grid with its tie rule.
class WinnerTakesAll final : public Selector {
  public:
    explicit WinnerTakesAll(const CandidateGrid& grid);
    void update(const CostValue* plane, int i, int j) override;
    Winners winners() const;  // valid left all 0

  private:
    const CandidateGrid& grid_;
    std::size_t size_;
    bool first_minimum_;  // candidate order already is the tie order: keep the first minimum
    std::vector<CostValue> best_;
    std::vector<std::uint16_t> best_k_;  // k = j * cols + i
    std::vector<std::int64_t> best_key_;
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
