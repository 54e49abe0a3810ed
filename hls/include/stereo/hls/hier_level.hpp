// hier_level: one level of the hierarchical 2-D search as a streaming pipeline, one pixel step
// per call (model: stereo::hierarchical::match_level with the census cost and
// CaNeighbours::horizontal, docs/hierarchical.md "The levels in hardware"; RTL:
// rtl/stereo_hier_level.sv). The 1-D pipeline's stages on the level's COLS x ROWS candidates per
// pixel, label k = j * COLS + i:
//   census_transform -> level_cost (2-D candidates, outside on any side) -> aggregate (one plane
//   per candidate, the level's kernel) -> CA rule 1 (runs of COLS labels: the "d +- 1" of (i, j)
//   are (i -+ 1, j), none past the row's ends) -> CA rule 2 (every label) -> level_wta (the 2-D
//   tie key) -> the displacement and its validity.
//
// Candidates. REFINE = 0 (the quarter level): every displacement of the level's range, base
// (0, V_MIN) for every pixel, COLS x ROWS = (D/f) x (V/f); the base arguments are ignored.
// REFINE = 1 (half and full): the 3x3 around the pixel's prediction, base (bd, bv) from the
// caller, who is asked twice, as by the RTL: for req_x() / req_y() at the step that reads the
// pixel's codes, and for out_x() / out_y() when its winner leaves (winner()). The prediction is
// the coarser level's winner, which the caller holds anyway, so the base does not travel through
// the pipeline's row delays.
//
// Validity (stereo::hierarchical::level_valid), reach = radius + (use_ca ? 1 : 0):
//   reach <= x < W - reach,  reach <= y < H - reach,  x - d >= reach,  reach <= y + v < H - reach.
// Input: the level's pixel pairs in raster order with their coordinates; after the frame's last
// pixel the caller keeps stepping with pixels below the frame (any data) until the last winner is
// out (run_level in hls/src/hierarchical.cpp), as stereo_hls_top flushes.
#pragma once

#include "stereo/hls/aggregate.hpp"
#include "stereo/hls/ca_rule.hpp"
#include "stereo/hls/census.hpp"
#include "stereo/hls/level_cost.hpp"
#include "stereo/hls/level_wta.hpp"
#include "stereo/hls/types.hpp"

namespace stereo::hls {

// A level's runtime configuration, its RTL's cfg_* ports: the size, the kernel (a window smaller
// than WINDOW centred in its taps, zeros around it), its half side (the validity border only) and
// whether the CA rules run.
template <int WINDOW>
struct LevelConfig {
    int width = 0;
    int height = 0;
    int radius = 0;
    tap_t kernel[WINDOW] = {};
    bool use_ca = true;
};

// The displacement that won at the output pixel, and whether the level's border rule keeps it.
struct LevelWinner {
    int d = 0;
    int v = 0;
    bool valid = false;
};

template <int WIDTH, int COLS, int ROWS, int V_MIN, int V_MAX, int WINDOW, bool REFINE>
class hier_level {
  public:
    static constexpr int kCols = COLS;
    static constexpr int kRows = ROWS;
    static constexpr int kLabels = COLS * ROWS;
    static constexpr int kVMin = V_MIN;
    static constexpr int kVMax = V_MAX;
    static constexpr int kWidth = WIDTH;
    static constexpr int kWindow = WINDOW;
    static constexpr bool kRefine = REFINE;
    static_assert(!REFINE ? ROWS == V_MAX - V_MIN + 1 : (COLS == 3 && ROWS == 3),
                  "REFINE = 0: one candidate row per offset V_MIN .. V_MAX; REFINE = 1: a 3x3");

    // Every stage's coordinates to "no pixel"; memories keep their contents.
    void reset() { reset_stages(census_, cost_, aggregate_, rule1_, rule2_, wta_); }

    // The pixel whose base the next step() takes.
    coord_t req_x() const { return cost_.req_x(); }
    coord_t req_y() const { return cost_.req_y(); }

    // One pixel step with the pair at (x, y) and the base of (req_x(), req_y()); the stages are
    // stepped from the last to the first, each reading the registers of the one before as they
    // were before this step.
    void step(coord_t x, coord_t y, const Rgb& left, const Rgb& right,
              const LevelConfig<WINDOW>& cfg, int in_base_d, int in_base_v) {
#pragma HLS INLINE
        wta_.step(rule2_.out_x(), rule2_.out_y(), rule2_.out_data());
        rule2_.step(rule1_.out_x(), rule1_.out_y(), rule1_.out_data(), cfg.width, cfg.height,
                    kLabels, cfg.use_ca);
        rule1_.step(aggregate_.out_x(), aggregate_.out_y(), aggregate_.out_data(), cfg.width,
                    cfg.height, kLabels, cfg.use_ca);
        aggregate_.step(cost_.out_x(), cost_.out_y(), cost_.out_data(), cfg.width, cfg.height,
                        cfg.kernel);
        cost_.step(census_.out_x(), census_.out_y(), census_.out_left(), census_.out_right(),
                   cfg.width, cfg.height, REFINE ? in_base_d : 0, REFINE ? in_base_v : V_MIN);
        census_.step(x, y, left, right, cfg.width, cfg.height);
    }

    // The WTA's register, which is the output register.
    coord_t out_x() const {
        return wta_.out_x();
    }
    coord_t out_y() const {
        return wta_.out_y();
    }

    // The winner of (out_x(), out_y()) with that pixel's base (REFINE = 1), combinational.
    LevelWinner winner(const LevelConfig<WINDOW>& cfg, int out_base_d, int out_base_v) const {
        const int label = wta_.out_label();
        const int d = (REFINE ? out_base_d : 0) + label % COLS;
        const int v = (REFINE ? out_base_v : V_MIN) + label / COLS;
        const int reach = cfg.radius + (cfg.use_ca ? 1 : 0);
        const int x = out_x();
        const int y = out_y();
        const bool valid = x >= reach && x < cfg.width - reach && y >= reach &&
                           y < cfg.height - reach && x - d >= reach && y + v >= reach &&
                           y + v < cfg.height - reach;
        return {d, v, valid};
    }

  private:
    census_transform<WIDTH> census_;
    level_cost<WIDTH, COLS, ROWS, V_MIN, V_MAX> cost_;
    aggregate<WIDTH, kLabels, WINDOW> aggregate_;
    ca_rule1<WIDTH, kLabels, COLS> rule1_;
    ca_rule2<WIDTH, kLabels> rule2_;
    level_wta<COLS, ROWS, REFINE, V_MIN> wta_;
};

}  // namespace stereo::hls
