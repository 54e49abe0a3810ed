// Independent implementations of the pipeline used only to check the golden model.
#pragma once

#include <string>

#include "stereo/pipeline.hpp"

namespace stereo::naive {

// Obviously-correct integer versions: direct 2-D window sums, integer division for the
// rounded 1/9 and 1/1.3, no separability, no incremental tricks. They must equal the
// optimised stages of pipeline.hpp exactly.
Dsi cost(const Image& left, const Image& right, int ndisp, int min_disp = 0);
Dsi aggregate(const Dsi& cost, const std::vector<std::int32_t>& kernel);
Dsi ca_rule1(const Dsi& dsi);
Dsi ca_rule2(const Dsi& dsi);
DisparityMap wta(const Dsi& dsi, const InvalidBorder& border);
// The naive volume of the cost named `name` (stereo::cost_names()).
Dsi cost_volume(const std::string& name, const Image& left, const Image& right, int ndisp,
                int min_disp = 0);
DisparityMap match(const Image& left, const Image& right, const MatchParams& params);
// Stage 6 by its definition over a whole final volume: every label scanned for the winner, the
// second-best cost and the right image's winner; the parabola vertex in double precision.
// Stage 6 along a search direction: label k of pixel (x, y) compares it with the partner pixel
// (x - d step_x, y - d step_y), d = min_disp + k; the border rule keeps both pixels `reach` inside
// the image, and the left-right check finds the partner pixel's own winner among the reference
// pixels that see it. validate() below is the horizontal case (1, 0); the quad pairs use (0, 1)
// and (1, 1).
ValidatedDisparity validate_along(const Dsi& dsi, int step_x, int step_y, int min_disp,
                                  const ValidationParams& params, int reach);
ValidatedDisparity validate(const Dsi& dsi, int min_disp, const ValidationParams& params,
                            const InvalidBorder& border);
// Stage 6 over the ASW matcher's volume (docs/asw.md, "Border and validity"): label k of pixel
// (x, y) is a candidate only where its match x - d (d = min_disp + k) lies inside the right image,
// whatever its cell holds. A label that is no candidate is never the winner, the second cost or
// a parabola point (no sub-pixel offset next to it); a pixel with no candidate at all is invalid
// (border) with certainty 0. No invalid border otherwise: the support region is clipped.
ValidatedDisparity validate_inside_matches(const Dsi& dsi, int min_disp,
                                           const ValidationParams& params);
ValidatedDisparity match_validated(const Image& left, const Image& right,
                                   const MatchParams& params);

}  // namespace stereo::naive

namespace stereo::census::naive {

// Census cost by its definition: codes recomputed for every pixel pair from the naive luma,
// bits counted one by one.
Dsi cost(const Image& left, const Image& right, int ndisp, int min_disp = 0);

// The census cost of left pixel (x, y) against right pixel (xr, yr), both inside their images,
// from grey images (edge_frontend::naive::luma): the differing code bits, one by one, times
// census::kWeight.
int pixel_cost(const Image& left_grey, int x, int y, const Image& right_grey, int xr, int yr);

}  // namespace stereo::census::naive

namespace stereo::lcdm::naive {

// LCDM cost by its definition (docs/fixed-point.md): every pixel converted again for every
// comparison, the trigonometric table entries from std::cos / std::sin on the spot, an integer
// square root bit by bit. Throws like the plug-in on a grey image. Label k is d = min_disp + k.
Dsi cost(const Image& left, const Image& right, int ndisp, int dark_floor, int min_disp = 0);
Dsi cost(const Image& left, const Image& right, int ndisp);
// The cost of left pixel (x, y) against right pixel (xr, yr), both inside, by the definition.
int pixel_cost(const Image& left, int x, int y, const Image& right, int xr, int yr, int dark_floor);

}  // namespace stereo::lcdm::naive

namespace stereo::zncc::naive {

// ZNCC cost by its definition: the 15x15 window summed directly for every cell. Label k is
// d = min_disp + k.
Dsi cost(const Image& left, const Image& right, int ndisp, int min_disp = 0);

}  // namespace stereo::zncc::naive

namespace stereo::floating {

// The same algorithm in double precision: exact normalised Gaussian weights, exact 1/9 and
// 1/1.3, no rounding anywhere. Used to measure what the fixed-point form changes.
DisparityMap match(const Image& left, const Image& right, const MatchParams& params);

}  // namespace stereo::floating
