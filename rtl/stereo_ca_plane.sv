// stereo_ca_plane: the shared skeleton of the two CA rules (docs/fixed-point.md stages 3 and 4):
// the 3x3 in-plane window of every disparity (stereo_window3x3: line buffers, coordinates, zero
// padding at the borders), the per-cell update selected by RULE, and the result register.
//
//   RULE 1 (model stereo::ca_rule1): a cell whose d-1 or d+1 neighbour (d+1 < cfg_ndisp) agrees
//          with it becomes round(sum of its 3x3 in-plane neighbourhood / 9), zero padding outside
//          the frame, (sum * MEAN9_MUL + 2^(MEAN9_SHIFT-1)) >> MEAN9_SHIFT.
//   RULE 2 (model stereo::ca_rule2): a cell with at least RULE2_MIN_COUNT of its 8 in-plane
//          neighbours inside the frame agreeing with it becomes round(c / 1.3) =
//          (c * DIV13_MUL + 2^(DIV13_SHIFT-1)) >> DIV13_SHIFT.
// "Agrees" is fx_pkg::agrees, 2|n - c| < c. With cfg_use_ca low every cell passes unchanged.
// Output pixel = input pixel moved back one row and one column. Latency: W + 3 pixel steps
// (the window's input register, the centre one row and one column back, the result register).
// stereo_top instantiates it twice: as ca_rule1 (RULE 1) and ca_rule2 (RULE 2).
`default_nettype none

module stereo_ca_plane #(
    parameter int WIDTH = 64,  // longest row
    parameter int NDISP = 16,  // disparities in parallel
    parameter int RULE  = 1    // 1 or 2
) (
    input  wire logic                              clk,
    input  wire logic                              rst,  // clears coordinates only
    input  wire logic                              ce,
    input  wire fx_pkg::coord_t                    in_x,
    input  wire fx_pkg::coord_t                    in_y,
    input  wire logic [NDISP*fx_pkg::AGG_BITS-1:0] in_data,
    input  wire fx_pkg::cfg_size_t                 cfg_width,
    input  wire fx_pkg::cfg_size_t                 cfg_height,
    // Rule 2 does not look across planes.
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire fx_pkg::cfg_ndisp_t                cfg_ndisp,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire logic                              cfg_use_ca,
    output      fx_pkg::coord_t                    out_x,
    output      fx_pkg::coord_t                    out_y,
    output      logic [NDISP*fx_pkg::AGG_BITS-1:0] out_data
);
  localparam int BITS = fx_pkg::AGG_BITS;
  localparam int SUM_BITS = fx_pkg::CA_SUM_BITS;
  localparam int COLUMN = NDISP * BITS;
  localparam int CENTRE = 4;  // slot of (0, 0)

  initial begin
    assert (RULE == 1 || RULE == 2);
  end

  fx_pkg::coord_t centre_x, centre_y;
  logic [9*COLUMN-1:0] window;
  logic [8:0] in_frame;
  stereo_window3x3 #(
      .WIDTH(WIDTH),
      .BITS (BITS),
      .NDISP(NDISP)
  ) neighbourhood (
      .clk(clk),
      .rst(rst),
      .ce(ce),
      .in_x(in_x),
      .in_y(in_y),
      .in_data(in_data),
      .cfg_width(cfg_width),
      .cfg_height(cfg_height),
      .centre_x(centre_x),
      .centre_y(centre_y),
      .window_data(window),
      .in_frame(in_frame)
  );

  logic [COLUMN-1:0] result;
  generate
    for (genvar d = 0; d < NDISP; d++) begin : g_disparity
      logic [BITS-1:0] centre;
      assign centre = window[CENTRE*COLUMN + d*BITS +: BITS];
      if (RULE == 1) begin : g_rule1
        logic below_agrees, above_agrees;
        if (d > 0) begin : g_below
          assign below_agrees = fx_pkg::agrees(window[CENTRE*COLUMN + (d-1)*BITS +: BITS], centre);
        end else begin : g_no_below
          assign below_agrees = 1'b0;
        end
        if (d + 1 < NDISP) begin : g_above
          assign above_agrees = d + 1 < $signed(32'(cfg_ndisp)) &&
                                fx_pkg::agrees(window[CENTRE*COLUMN + (d+1)*BITS +: BITS], centre);
        end else begin : g_no_above
          assign above_agrees = 1'b0;
        end
        always_comb begin
          logic [SUM_BITS-1:0] sum;
          logic [31:0] product;
          sum = '0;
          for (int slot = 0; slot < 9; slot++) begin
            if (in_frame[slot]) sum = sum + SUM_BITS'(window[slot*COLUMN + d*BITS +: BITS]);
          end
          product = 32'(sum) * 32'(fx_pkg::MEAN9_MUL) + 32'(1 << (fx_pkg::MEAN9_SHIFT - 1));
          result[d*BITS +: BITS] = (cfg_use_ca && (below_agrees || above_agrees))
                                       ? BITS'(product >> fx_pkg::MEAN9_SHIFT) : centre;
        end
      end else begin : g_rule2
        always_comb begin
          logic [3:0] count;
          logic [31:0] product;
          count = '0;
          for (int slot = 0; slot < 9; slot++) begin
            // A neighbour outside the frame is zero padding, and zero never agrees.
            if (slot != CENTRE && in_frame[slot] &&
                fx_pkg::agrees(window[slot*COLUMN + d*BITS +: BITS], centre)) begin
              count = count + 4'd1;
            end
          end
          product = 32'(centre) * 32'(fx_pkg::DIV13_MUL) + 32'(1 << (fx_pkg::DIV13_SHIFT - 1));
          result[d*BITS +: BITS] = (cfg_use_ca && $signed(32'(count)) >= fx_pkg::RULE2_MIN_COUNT)
                                       ? BITS'(product >> fx_pkg::DIV13_SHIFT) : centre;
        end
      end
    end
  endgenerate

  always_ff @(posedge clk) begin
    if (ce) out_data <= result;
  end
  stereo_coord_reg coordinates (
      .in_x(centre_x),
      .in_y(centre_y),
      .*
  );
endmodule

`default_nettype wire
