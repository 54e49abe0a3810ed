// stereo_prediction_ring: the coarse level's winners that a refinement level of the hierarchical
// search still needs (stereo_hier_levels; model: stereo::hierarchical::refine_grid). RING rows of
// the coarse level, row r in slot r mod RING (LUT RAM, two reads), and the count of rows written
// in this frame. A fine pixel (x, y) reads its parent (min(x/2, Wc-1), min(y/2, Hc-1)) and gets
// its base: the parent's winner (dc, vc) up-scaled x2 and clamped per axis into
// [min + 1, max - 1] of the fine level's range, minus (1, 1), so the 3x3 lies in the range.
// Port a: the pixel whose costs the fine level computes next (ready when its parent row has
// been written); port b: the fine level's winner, whose parent row is the oldest still needed.
`default_nettype none
`include "stereo_assert.svh"

module stereo_prediction_ring #(
    parameter int WIDTH  = 32,  // longest coarse row
    parameter int RING   = 8,   // coarse rows held (a power of two)
    parameter int D_FINE = 8,   // the fine level's horizontal labels: d = 0 .. D_FINE-1
    parameter int V_MIN  = -4,  // the fine level's vertical offsets V_MIN .. V_MAX
    parameter int V_MAX  = 3
) (
    input  wire logic                                clk,
    input  wire logic                                new_frame,  // forget the rows written
    input  wire fx_pkg::cfg_size_t                   cfg_width,  // the coarse frame
    input  wire fx_pkg::cfg_size_t                   cfg_height,
    input  wire logic                                write,      // a coarse winner
    input  wire fx_pkg::coord_t                      write_x,
    input  wire fx_pkg::coord_t                      write_y,
    input  wire logic [fx_pkg::DISP_BITS-1:0]        write_d,
    input  wire logic signed [fx_pkg::DISP_BITS-1:0] write_v,
    input  wire fx_pkg::coord_t                      a_x,
    input  wire fx_pkg::coord_t                      a_y,
    output      logic [fx_pkg::DISP_BITS-1:0]        a_base_d,
    output      logic signed [fx_pkg::DISP_BITS-1:0] a_base_v,
    output      logic                                a_ready,
    input  wire fx_pkg::coord_t                      b_x,
    input  wire fx_pkg::coord_t                      b_y,
    output      logic [fx_pkg::DISP_BITS-1:0]        b_base_d,
    output      logic signed [fx_pkg::DISP_BITS-1:0] b_base_v,
    output      fx_pkg::coord_t                      oldest_needed  // b's parent row (0 before)
);
  localparam int SLOT_BITS = $clog2(RING);
  localparam int ADDR_BITS = $clog2(RING * WIDTH);
  localparam int D = fx_pkg::DISP_BITS;
  `STEREO_ASSERT(ring_power_of_two, RING >= 2 && (1 << SLOT_BITS) == RING,
                 "RING must be a power of two, at least 2")
  `STEREO_ASSERT(fine_range, D_FINE >= 3 && V_MAX - V_MIN >= 2,
                 "the fine level needs 3 labels per axis")

  logic [2*D-1:0] mem[RING * WIDTH];
  fx_pkg::coord_t rows_done;
  always_ff @(posedge clk) begin
    if (write) mem[ADDR_BITS'(32'(write_y[SLOT_BITS-1:0]) * WIDTH + 32'(write_x))] <= {write_d, write_v};
    if (new_frame) rows_done <= '0;
    else if (write && write_x == 16'($signed(32'(cfg_width)) - 1)) rows_done <= write_y + 16'sd1;
  end

  // The parent of a fine coordinate, clamped into the coarse frame (negative: 0).
  function automatic fx_pkg::coord_t parent(input fx_pkg::coord_t fine, input fx_pkg::cfg_size_t size);
    if (fine < 0) parent = '0;
    else if ((32'(fine) >>> 1) >= 32'(size)) parent = 16'($signed(32'(size)) - 1);
    else parent = fine >>> 1;
  endfunction
  function automatic logic signed [D+1:0] clamp(input logic signed [D+1:0] value,
                                               input logic signed [D+1:0] low,
                                               input logic signed [D+1:0] high);
    if (value < low) clamp = low;
    else if (value > high) clamp = high;
    else clamp = value;
  endfunction

  fx_pkg::coord_t a_px, a_py, b_px, b_py;
  logic [2*D-1:0] a_word, b_word;
  assign a_px = parent(a_x, cfg_width);
  assign a_py = parent(a_y, cfg_height);
  assign b_px = parent(b_x, cfg_width);
  assign b_py = parent(b_y, cfg_height);
  assign a_word = mem[ADDR_BITS'(32'(a_py[SLOT_BITS-1:0]) * WIDTH + 32'(a_px))];
  assign b_word = mem[ADDR_BITS'(32'(b_py[SLOT_BITS-1:0]) * WIDTH + 32'(b_px))];
  assign a_ready = a_y < 0 || a_py < rows_done;
  assign oldest_needed = (b_y < 0) ? '0 : b_py;

  // Up-scaled x2 and clamped into [min + 1, max - 1], minus 1.
  always_comb begin
    a_base_d = D'(clamp({1'b0, a_word[2*D-1:D], 1'b0}, (D + 2)'(1), (D + 2)'(D_FINE - 2)) - (D + 2)'(1));
    a_base_v = D'(clamp({a_word[D-1], a_word[D-1:0], 1'b0}, (D + 2)'(V_MIN + 1), (D + 2)'(V_MAX - 1)) - (D + 2)'(1));
    b_base_d = D'(clamp({1'b0, b_word[2*D-1:D], 1'b0}, (D + 2)'(1), (D + 2)'(D_FINE - 2)) - (D + 2)'(1));
    b_base_v = D'(clamp({b_word[D-1], b_word[D-1:0], 1'b0}, (D + 2)'(V_MIN + 1), (D + 2)'(V_MAX - 1)) - (D + 2)'(1));
  end
endmodule

`default_nettype wire
