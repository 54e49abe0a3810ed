// stereo_level_cost: stage 1 of a hierarchical level (model: stereo::cost_plane over a
// CandidateGrid with the census cost; docs/hierarchical.md "Candidates and the DSI of a level",
// "The streaming core"). For the pixel (x, y) and its base (bd, bv) it computes the cost of every
// candidate (i, j), label k = j * COLS + i:
//   popcount(L(x, y) ^ R(x - bd - i, y + bv + j)) * CENSUS_WEIGHT,
// or COST_OUTSIDE where that right pixel lies outside the frame, on any side (a 2-D candidate
// can leave the frame above and below, not only on the left as in stereo_cost).
//
// Memory: the census codes of the last SLOTS = V_MAX - V_MIN + 2 rows of both images, row r in
// slot r mod SLOTS. The right rows are split into COLS banks by column mod COLS, so the COLS
// consecutive columns x - bd - COLS + 1 .. x - bd come out of COLS one-port memories in one
// read, and every slot has its own banks, so the ROWS candidate rows (distinct rows) read in the
// same step. The left codes wait for their last right row in one memory of SLOTS rows. The bank
// count is COLS rounded up to a power of two (BANKS), so that a column's bank and address are its
// low and high bits, not a division by COLS; the slot of a candidate row is the slot of the
// pixel's row plus its offset, brought back into 0 .. SLOTS-1 by one addition or subtraction.
//
// Timing: the codes of pixel (in_x, in_y) (stereo_census's output: raster order, flush rows
// beyond the frame) are written at their step. The pixel matched at a step is the one whose last
// right pixel, (x, y + V_MAX), arrived at the step before: (req_x, req_y) = (the previous step's
// in_x, its in_y - V_MAX), whose base the caller puts on in_base_d / in_base_v during that
// step. The step reads every bank at that pixel's columns and registers which slot and bank
// each candidate reads and whether it lies outside; the next step computes the costs into
// out_data. Latency: 2 pixel steps from the codes' arrival at (x, y + V_MAX); one pixel per ce.
// SLOTS exceeds the rows a step reads by one, so a write never meets a read of the same row.
// Time-multiplexed lanes (LANES < COLS * ROWS, the stage contract of docs/rtl.md): the costs are
// computed and registered at the step as with G = 1; out_data is the registered pixel's group
// `group` (labels [group*LANES +: LANES]).
// Reset clears the coordinates only; stale codes are never read by a real pixel (a row is
// written before any pixel reads it).
`default_nettype none
`include "stereo_assert.svh"

module stereo_level_cost #(
    parameter int WIDTH = 32,  // longest row of the level
    parameter int COLS  = 3,   // candidate columns (horizontal displacements per row)
    parameter int ROWS  = 3,   // candidate rows (vertical displacements)
    parameter int V_MIN = -2,  // the level's smallest vertical offset
    parameter int V_MAX = 1,   // the level's largest vertical offset
    parameter int LANES = COLS * ROWS  // labels handed on per clock (divides COLS * ROWS)
) (
    input  wire logic                                        clk,
    input  wire logic                                        rst,  // clears coordinates only
    input  wire logic                                        ce,   // the pixel step
    /* verilator lint_off UNUSEDSIGNAL */  // G = 1: always 0
    input  wire logic [(((COLS * ROWS) / LANES > 1) ? $clog2((COLS * ROWS) / LANES) : 1)-1:0] group,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire fx_pkg::coord_t                              in_x,
    input  wire fx_pkg::coord_t                              in_y,
    input  wire logic [23:0]                                 in_left,   // census code
    input  wire logic [23:0]                                 in_right,  // census code
    /* verilator lint_off UNUSEDSIGNAL */  // reads width and height only
    input  wire fx_pkg::config_t                             cfg,
    /* verilator lint_on UNUSEDSIGNAL */
    // The pixel matched at the next step, and its base (given by the caller during this step).
    output      fx_pkg::coord_t                              req_x,
    output      fx_pkg::coord_t                              req_y,
    input  wire logic [fx_pkg::DISP_BITS-1:0]                in_base_d,  // >= 0
    input  wire logic signed [fx_pkg::DISP_BITS-1:0]         in_base_v,
    output      fx_pkg::coord_t                              out_x,
    output      fx_pkg::coord_t                              out_y,
    output      fx_pkg::coord_t                              out_next_y,  // stereo_aggregate in_next_y
    output      logic [LANES*fx_pkg::COST_BITS-1:0]          out_data
);
  localparam int SLOTS = V_MAX - V_MIN + 2;
  localparam int SLOT_BITS = $clog2(SLOTS);
  localparam int BANK_SHIFT = (COLS > 1) ? $clog2(COLS) : 0;
  localparam int BANKS = 1 << BANK_SHIFT;
  localparam int BANK_DEPTH = (WIDTH + BANKS - 1) / BANKS;
  localparam int BANK_BITS = (BANK_DEPTH > 1) ? $clog2(BANK_DEPTH) : 1;
  localparam int LEFT_BITS = $clog2(SLOTS * WIDTH);
  localparam int COST_BITS = fx_pkg::COST_BITS;
  localparam int BANK_SELECT_BITS = (BANKS > 1) ? BANK_SHIFT : 1;
  localparam int LABELS = COLS * ROWS;
  localparam int GROUPS = LABELS / LANES;
  // Rows are biased by a multiple of SLOTS before the modulo, so that the operand is
  // non-negative and narrow (ROW_MOD_BITS): rows from -ROW_BIAS on (the level's rows and its
  // flush rows lie far inside).
  localparam int ROW_BIAS = SLOTS * ((256 + SLOTS - 1) / SLOTS);
  localparam int ROW_MOD_BITS = 13;

  `STEREO_ASSERT(grid_size, COLS >= 1 && ROWS >= 1 && ROWS <= V_MAX - V_MIN + 1,
                 "COLS >= 1 and ROWS in 1 .. V_MAX - V_MIN + 1")
  `STEREO_ASSERT(offset_range, V_MIN <= -1 && V_MAX >= 0 && V_MAX - V_MIN <= 126,
                 "the vertical offsets V_MIN .. V_MAX must contain -1 and 0 and fit a byte")
  `STEREO_ASSERT(lanes_divide_labels, LANES >= 1 && LABELS % LANES == 0,
                 "LANES must divide COLS * ROWS")

  function automatic logic [SLOT_BITS-1:0] slot_of(input logic signed [17:0] row);
    slot_of = SLOT_BITS'($unsigned(ROW_MOD_BITS'(row + 18'(ROW_BIAS))) % ROW_MOD_BITS'(SLOTS));
  endfunction
  // The slot of a row `offset` rows from a row in slot `slot`, |offset| < SLOTS.
  function automatic logic [SLOT_BITS-1:0] slot_plus(input logic [SLOT_BITS-1:0] slot,
                                                     input logic signed [8:0] offset);
    logic signed [9:0] sum;
    sum = 10'(slot) + 10'(offset);
    if (sum < 0) sum = sum + 10'(SLOTS);
    else if (sum >= 10'(SLOTS)) sum = sum - 10'(SLOTS);
    slot_plus = SLOT_BITS'(sum);
  endfunction

  // ---- the previous step's pixel and the pixel it completes --------------------------------
  fx_pkg::coord_t prev_x, prev_y;
  stereo_coord_reg previous (
      .clk(clk), .rst(rst), .ce(ce), .in_x(in_x), .in_y(in_y), .out_x(prev_x), .out_y(prev_y));
  assign req_x = prev_x;
  assign req_y = (prev_y == fx_pkg::NO_PIXEL) ? fx_pkg::NO_PIXEL
                                               : 16'(prev_y - 16'(V_MAX));

  // ---- writes -------------------------------------------------------------------------------
  logic write;
  logic [SLOT_BITS-1:0] write_slot;
  assign write = ce && in_y != fx_pkg::NO_PIXEL && in_x >= 0 && in_y >= 0 &&
                 32'(in_x) < 32'(cfg.width) && 32'(in_y) < 32'(cfg.height);
  assign write_slot = slot_of(18'(in_y));

  logic [SLOT_BITS-1:0] req_slot;  // the slot of row req_y
  assign req_slot = slot_of(18'(req_y));
  logic [23:0] left_mem[SLOTS * WIDTH];
  logic [23:0] left_code;  // L(req) after the step
  always_ff @(posedge clk) begin
    if (write) left_mem[LEFT_BITS'(32'(write_slot) * WIDTH + 32'(in_x))] <= in_left;
    if (ce) left_code <= left_mem[LEFT_BITS'(32'(req_slot) * WIDTH +
                                              ((req_x >= 0 && 32'(req_x) < WIDTH) ? 32'(req_x) : 0))];
  end

  // ---- the candidates' columns and rows -------------------------------------------------------
  // Candidate i reads column c_i = x - bd - i; each bank holds exactly one of the COLS
  // consecutive columns.
  logic signed [17:0] column[COLS];
  logic [BANK_BITS-1:0] bank_address[BANKS];  // per bank
  logic [BANK_SELECT_BITS-1:0] column_bank[COLS];  // per candidate column
  logic column_outside[COLS];
  always_comb begin
    for (int b = 0; b < BANKS; b++) bank_address[b] = '0;
    for (int i = 0; i < COLS; i++) begin
      column[i] = 18'(req_x) - 18'(in_base_d) - 18'(i);
      column_bank[i] = (BANKS > 1) ? BANK_SELECT_BITS'(column[i]) : '0;
      column_outside[i] = column[i] < 0 || 32'(column[i]) >= 32'(cfg.width);
      if (!column_outside[i])
        bank_address[column_bank[i]] = BANK_BITS'(column[i] >>> BANK_SHIFT);
    end
  end
  logic signed [17:0] row[ROWS];
  logic [SLOT_BITS-1:0] row_slot[ROWS];
  logic row_outside[ROWS];
  always_comb begin
    for (int j = 0; j < ROWS; j++) begin
      row[j] = 18'(req_y) + 18'(in_base_v) + 18'(j);
      row_slot[j] = slot_plus(req_slot, 9'(in_base_v) + 9'(j));
      row_outside[j] = req_y == fx_pkg::NO_PIXEL || row[j] < 0 || 32'(row[j]) >= 32'(cfg.height);
    end
  end

  // ---- the right banks: one memory per slot and bank, read at every step -----------------------
  // The bank and address of the written column (unsigned: the column is not negative there).
  logic [BANK_SELECT_BITS-1:0] write_bank;
  logic [BANK_BITS-1:0] write_address;
  assign write_bank = (BANKS > 1) ? BANK_SELECT_BITS'($unsigned(in_x)) : '0;
  assign write_address = BANK_BITS'($unsigned(in_x) >> BANK_SHIFT);
  logic [23:0] bank_code[SLOTS][BANKS];  // after the step
  for (genvar s = 0; s < SLOTS; s++) begin : g_slot
    for (genvar b = 0; b < BANKS; b++) begin : g_bank
      logic [23:0] mem[BANK_DEPTH];
      always_ff @(posedge clk) begin
        if (write && write_slot == SLOT_BITS'(s) && write_bank == BANK_SELECT_BITS'(b))
          mem[write_address] <= in_right;
        if (ce) bank_code[s][b] <= mem[bank_address[b]];
      end
    end
  end

  // ---- the selection, registered beside the read ---------------------------------------------
  fx_pkg::coord_t read_x, read_y;
  logic [SLOT_BITS-1:0] read_slot[ROWS];
  logic [BANK_SELECT_BITS-1:0] read_bank[COLS];
  logic read_outside[ROWS][COLS];
  stereo_coord_reg read_coordinates (
      .clk(clk), .rst(rst), .ce(ce), .in_x(req_x), .in_y(req_y), .out_x(read_x), .out_y(read_y));
  always_ff @(posedge clk) begin
    if (ce) begin
      for (int j = 0; j < ROWS; j++) read_slot[j] <= row_slot[j];
      for (int i = 0; i < COLS; i++) read_bank[i] <= column_bank[i];
      for (int j = 0; j < ROWS; j++)
        for (int i = 0; i < COLS; i++) read_outside[j][i] <= row_outside[j] || column_outside[i];
    end
  end

  // ---- the costs --------------------------------------------------------------------------------
  stereo_coord_reg out_coordinates (
      .clk(clk), .rst(rst), .ce(ce), .in_x(read_x), .in_y(read_y), .out_x(out_x), .out_y(out_y));
  assign out_next_y = read_y;
  logic [23:0] right_code[ROWS][COLS];  // R(x - bd - i, y + bv + j)
  logic [LABELS*COST_BITS-1:0] costs, registered_costs;
  always_comb begin
    for (int j = 0; j < ROWS; j++) begin
      for (int i = 0; i < COLS; i++) begin
        right_code[j][i] = bank_code[read_slot[j]][read_bank[i]];
        costs[(j * COLS + i) * COST_BITS +: COST_BITS] =
            read_outside[j][i] ? COST_BITS'(fx_pkg::COST_OUTSIDE)
                               : COST_BITS'($countones(left_code ^ right_code[j][i]) *
                                            fx_pkg::CENSUS_WEIGHT);
      end
    end
  end
  always_ff @(posedge clk) begin
    if (ce) registered_costs <= costs;
  end
  generate
    if (GROUPS > 1) begin : g_group
      assign out_data = registered_costs[32'(group) * LANES * COST_BITS +: LANES * COST_BITS];
    end else begin : g_all
      assign out_data = registered_costs;
    end
  endgenerate
endmodule

`default_nettype wire
