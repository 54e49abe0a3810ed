// stereo_ca_plane: the shared skeleton of the two CA rules (docs/fixed-point.md stages 3 and 4):
// the 3x3 in-plane window of every disparity (stereo_window3x3: line buffers, coordinates, zero
// padding at the borders), the per-cell update selected by RULE, and the result register.
//
//   CA_RULE1 (model stereo::ca_rule1): a cell whose d-1 or d+1 neighbour (d+1 < cfg.ndisp) agrees
//            with it becomes round(sum of its 3x3 in-plane neighbourhood / 9), zero padding outside
//            the frame, (sum * MEAN9_MUL + 2^(MEAN9_SHIFT-1)) >> MEAN9_SHIFT.
//   CA_RULE2 (model stereo::ca_rule2): a cell with at least RULE2_MIN_COUNT of its 8 in-plane
//            neighbours inside the frame agreeing with it becomes round(c / 1.3) =
//            (c * DIV13_MUL + 2^(DIV13_SHIFT-1)) >> DIV13_SHIFT.
// "Agrees" is fx_pkg::agrees, 2|n - c| < c. With cfg.use_ca low every cell passes unchanged.
// Output pixel = input pixel moved back one row and one column. Latency: W + 3 pixel steps
// (the window's input register, the centre one row and one column back, the result register).
// stereo_top instantiates it twice: as ca_rule1 (RULE = CA_RULE1) and ca_rule2 (CA_RULE2).
//
// Time-multiplexed lanes (LANES < NDISP, docs/rtl.md): the clock of label group g (`group`; the
// step, ce, at group G-1) computes labels d = g*LANES + l, l < LANES, on LANES copies of the
// rule. Rule 1's neighbours across the group boundary: d-1 of the first lane is the previous
// group's last centre, kept in a register when that group advanced; d+1 of the last lane is the
// next group's first centre (stereo_window3x3 next_centre). The stage hands on one group per
// clock: in_data is the producer's result of this clock's group, which the window delays by 2G
// group clocks in a RAM ring, and out_data is this clock's result, unregistered (the consumer
// delays it); out_x/out_y still step with ce. G = 1: in_data and out_data carry all labels and
// out_data is a register stepped with ce, as before lanes.
`default_nettype none
`include "stereo_assert.svh"

module stereo_ca_plane #(
    parameter int WIDTH = 64,  // longest row
    parameter int NDISP = 16,  // disparities in parallel
    parameter fx_pkg::ca_rule_e RULE = fx_pkg::CA_RULE1,  // CA_RULE1 or CA_RULE2
    parameter int LANES = NDISP,  // labels computed per clock (divides NDISP)
    // Rule 1: the labels form independent runs of SEGMENT consecutive labels, whose d-1 and d+1
    // neighbours are inside the run only (the hierarchical levels' candidate rows,
    // CaNeighbours::horizontal). A multiple of LANES, or a divisor of it.
    parameter int SEGMENT = NDISP,
    parameter bit RING_BLOCK_RAM = 1'b0,  // stereo_group_ring BLOCK_RAM (stereo_top)
    parameter int RING_BLOCK_MIN_FILL = 50  // stereo_group_ring BLOCK_MIN_FILL
) (
`include "stereo_stage_ports.svh"
    // G = 1: the pixel's NDISP values; G > 1: the producer's result of this clock's group.
    input  wire logic [LANES*fx_pkg::AGG_BITS-1:0] in_data,
    /* verilator lint_off UNUSEDSIGNAL */  // reads width, height, use_ca; ndisp with rule 1
    input  wire fx_pkg::config_t                   cfg,
    /* verilator lint_on UNUSEDSIGNAL */
    output      fx_pkg::coord_t                    out_x,
    output      fx_pkg::coord_t                    out_y,
    // G = 1: all labels, registered at ce; G > 1: this clock's group, combinational.
    output      logic [LANES*fx_pkg::AGG_BITS-1:0] out_data
);
  localparam int BITS = fx_pkg::AGG_BITS;
  localparam int SUM_BITS = fx_pkg::CA_SUM_BITS;
  localparam int GROUPS = NDISP / LANES;
  localparam int COLUMN = LANES * BITS;  // one group of one window position
  localparam int CENTRE = 4;  // slot of (0, 0)

  `STEREO_ASSERT(rule_known, RULE == fx_pkg::CA_RULE1 || RULE == fx_pkg::CA_RULE2,
                 "RULE must be CA_RULE1 or CA_RULE2")
  `STEREO_ASSERT(lanes_divide_ndisp, LANES >= 1 && NDISP % LANES == 0,
                 "LANES must be at least 1 and divide NDISP")
  `STEREO_ASSERT(segment_shape, SEGMENT >= 1 && NDISP % SEGMENT == 0 &&
                 (SEGMENT % LANES == 0 || LANES % SEGMENT == 0),
                 "SEGMENT must divide NDISP and be a multiple or a divisor of LANES")
  // Groups per run (SEGMENT a multiple of LANES); 0: a group holds whole runs.
  localparam int RUN_GROUPS = (SEGMENT % LANES == 0) ? SEGMENT / LANES : 0;

  fx_pkg::coord_t centre_x, centre_y;
  // The group of this clock; G = 1: 0 whatever the port carries (stage testbenches leave it open).
  logic [((GROUPS > 1) ? $clog2(GROUPS) : 1)-1:0] group_now;
  assign group_now = (GROUPS > 1) ? group : '0;

  logic [9*COLUMN-1:0] window;
  logic [8:0] in_frame;
  /* verilator lint_off UNUSEDSIGNAL */  // rule 2 and G = 1 do not look across groups
  logic [BITS-1:0] next_centre;  // centre of label (group+1)*LANES
  /* verilator lint_on UNUSEDSIGNAL */
  stereo_window3x3 #(
      .WIDTH(WIDTH),
      .BITS (BITS),
      .NDISP(NDISP),
      .LANES(LANES),
      .RING_BLOCK_RAM(RING_BLOCK_RAM),
      .RING_BLOCK_MIN_FILL(RING_BLOCK_MIN_FILL)
  ) neighbourhood (
      .clk(clk),
      .rst(rst),
      .ce(ce),
      .group(group_now),
      .next_centre(next_centre),
      .in_x(in_x),
      .in_y(in_y),
      .in_data(in_data),
      .cfg_width(cfg.width),
      .cfg_height(cfg.height),
      .centre_x(centre_x),
      .centre_y(centre_y),
      .window_data(window),
      .in_frame(in_frame)
  );

  // Rule 1: the previous group's last centre, label group*LANES - 1.
  /* verilator lint_off UNUSEDSIGNAL */  // rule 2 and G = 1 do not look across groups
  logic [BITS-1:0] previous_centre;
  /* verilator lint_on UNUSEDSIGNAL */
  generate
    if (GROUPS > 1 && RULE == fx_pkg::CA_RULE1) begin : g_previous_centre
      // Kept at every clock that processes a group (as in stereo_window3x3).
      always_ff @(posedge clk) begin
        if (ce || 32'(group_now) != GROUPS - 1)
          previous_centre <= window[CENTRE*COLUMN + (LANES-1)*BITS +: BITS];
      end
    end else begin : g_no_previous_centre
      assign previous_centre = '0;
    end
  endgenerate

  // The factored constant products below hold only for these reciprocals (fx_pkg, generated
  // from the model's stage table): elaboration stops if they ever change.
  `STEREO_ASSERT(mean9_factors, fx_pkg::MEAN9_MUL == 7 * 4161,
                 "the factored MEAN9_MUL product needs MEAN9_MUL = 7 * 4161")
  `STEREO_ASSERT(div13_factors, fx_pkg::DIV13_MUL == 25 * 4033,
                 "the factored DIV13_MUL product needs DIV13_MUL = 25 * 4033")

  // How many of eight flags are set, as boolean full and half adders: logic a few LUTs deep. A
  // running `count + 1` over the neighbours was eight small carry chains in a row, the one-label
  // iCE40 core's critical path (docs/synthesis.md).
  function automatic logic [3:0] count_ones8(input logic [7:0] f);
    logic s1, c1, s2, c2, s3, c3, s4, c4, s5, c5, s6, c6;
    // weight 1: f0+f1+f2, f3+f4+f5, f6+f7
    s1 = f[0] ^ f[1] ^ f[2];
    c1 = (f[0] & f[1]) | (f[0] & f[2]) | (f[1] & f[2]);
    s2 = f[3] ^ f[4] ^ f[5];
    c2 = (f[3] & f[4]) | (f[3] & f[5]) | (f[4] & f[5]);
    s3 = f[6] ^ f[7];
    c3 = f[6] & f[7];
    s4 = s1 ^ s2 ^ s3;  // bit 0
    c4 = (s1 & s2) | (s1 & s3) | (s2 & s3);
    // weight 2: c1 + c2 + c3 + c4
    s5 = c1 ^ c2 ^ c3;
    c5 = (c1 & c2) | (c1 & c3) | (c2 & c3);
    s6 = s5 ^ c4;  // bit 1
    c6 = s5 & c4;
    // weight 4: c5 + c6 (both set only when all eight flags are: 8)
    count_ones8 = {c5 & c6, c5 ^ c6, s6, s4};
  endfunction

  logic [COLUMN-1:0] result;
  generate
    for (genvar d = 0; d < LANES; d++) begin : g_disparity
      // Lane d computes label group*LANES + d.
      logic [BITS-1:0] centre;
      assign centre = window[CENTRE*COLUMN + d*BITS +: BITS];
      if (RULE == fx_pkg::CA_RULE1) begin : g_rule1
        logic below_agrees, above_agrees;
        // Inside the group a run starts at lanes that are multiples of SEGMENT (when a group
        // holds whole runs); across groups at groups that are multiples of RUN_GROUPS.
        if (d > 0 && (RUN_GROUPS != 0 || d % SEGMENT != 0)) begin : g_below
          assign below_agrees = fx_pkg::agrees(window[CENTRE*COLUMN + (d-1)*BITS +: BITS], centre);
        end else if (d == 0 && GROUPS > 1 && RUN_GROUPS > 1) begin : g_below_previous_group
          assign below_agrees = 32'(group_now) % RUN_GROUPS != 0 &&
                                fx_pkg::agrees(previous_centre, centre);
        end else begin : g_no_below
          assign below_agrees = 1'b0;
        end
        if (d + 1 < LANES && (RUN_GROUPS != 0 || (d + 1) % SEGMENT != 0)) begin : g_above
          assign above_agrees = 32'(group_now) * LANES + d + 1 < $signed(32'(cfg.ndisp)) &&
                                fx_pkg::agrees(window[CENTRE*COLUMN + (d+1)*BITS +: BITS], centre);
        end else if (d + 1 == LANES && GROUPS > 1 && RUN_GROUPS > 1) begin : g_above_next_group
          assign above_agrees = (32'(group_now) + 1) % RUN_GROUPS != 0 &&
                                32'(group_now) * LANES + d + 1 < $signed(32'(cfg.ndisp)) &&
                                fx_pkg::agrees(next_centre, centre);
        end else begin : g_no_above
          assign above_agrees = 1'b0;
        end
        always_comb begin
          logic [SUM_BITS-1:0] sum;
          logic [31:0] sum7, product;
          logic [SUM_BITS-1:0] term[9];
          for (int slot = 0; slot < 9; slot++) begin
            term[slot] = in_frame[slot] ? SUM_BITS'(window[slot*COLUMN + d*BITS +: BITS]) : '0;
          end
          // A balanced tree, four adders deep (a running sum was eight: the one-label core's
          // critical path once rule 2's count was a tree); the same integer, SUM_BITS holds 9
          // times the largest value.
          sum = ((term[0] + term[1]) + (term[2] + term[3])) +
                ((term[4] + term[5]) + (term[6] + term[7])) + term[8];
          // sum * MEAN9_MUL with MEAN9_MUL = 29127 = 7 * (2^12 + 2^6 + 1): three adders instead
          // of one per set bit (nine), exactly the same integer (checked at elaboration below).
          sum7 = (32'(sum) << 3) - 32'(sum);
`ifdef STEREO_TEST_BREAK_RULE1_ROUNDING
          // Test hook, never defined in a real build: rounds the mean down instead of to the
          // nearest, a known culprit for the co-simulation's stage localisation (docs/gtkwave.md).
          product = sum7 + (sum7 << 6) + (sum7 << 12);
`else
          product = sum7 + (sum7 << 6) + (sum7 << 12) + 32'(1 << (fx_pkg::MEAN9_SHIFT - 1));
`endif
          result[d*BITS +: BITS] = (cfg.use_ca && (below_agrees || above_agrees))
                                       ? BITS'(product >> fx_pkg::MEAN9_SHIFT) : centre;
        end
      end else begin : g_rule2
        always_comb begin
          logic [7:0] agreeing;
          logic [3:0] count;
          logic [31:0] centre25, product;
          for (int n = 0; n < 8; n++) begin
            // Neighbour n is slot n, then n + 1 past the centre. A neighbour outside the frame
            // is zero padding, and zero never agrees.
            agreeing[n] = in_frame[(n < CENTRE) ? n : n + 1] &&
                          fx_pkg::agrees(window[((n < CENTRE) ? n : n + 1)*COLUMN + d*BITS +: BITS],
                                         centre);
          end
          count = count_ones8(agreeing);
          // centre * DIV13_MUL with DIV13_MUL = 100825 = 25 * (2^12 - 2^6 + 1): four adders
          // instead of one per set bit (nine), the same integer (checked at elaboration below).
          centre25 = (32'(centre) << 4) + (32'(centre) << 3) + 32'(centre);
`ifdef STEREO_TEST_BREAK_RULE2_ROUNDING
          // Test hook, never defined in a real build: the quotient rounded down (see rule 1's).
          product = (centre25 << 12) - (centre25 << 6) + centre25;
`else
          product = (centre25 << 12) - (centre25 << 6) + centre25 +
                    32'(1 << (fx_pkg::DIV13_SHIFT - 1));
`endif
          result[d*BITS +: BITS] = (cfg.use_ca && $signed(32'(count)) >= fx_pkg::RULE2_MIN_COUNT)
                                       ? BITS'(product >> fx_pkg::DIV13_SHIFT) : centre;
        end
      end
    end
  endgenerate

  // G > 1: the group goes on as computed (the consumer's input ring registers it); G = 1: the
  // output register.
  stereo_stage_output #(.BITS(LANES * BITS), .REGISTERED(GROUPS == 1)) outputs (
      .in_x(centre_x), .in_y(centre_y), .in_data(result), .*);
endmodule

`default_nettype wire
