// tb_stereo_top: the self-checking SystemVerilog testbench of stereo_top (README.md). The frame
// configuration goes to the cfg_* ports, the vectors' pixels through s_axis with random gaps, and
// every m_axis beat is compared with the golden model's (tb_stereo_vectors). Ends with
// "tb_stereo_top: PASS ..." and $finish, or "... FAIL ..." and $fatal (a non-zero exit status).
// The parameters are stereo_top's: set them (-G / -g / generic) to the core under test.
`default_nettype none

module tb_stereo_top #(
    `include "tb_core_params.svh"
    parameter int SHIFT_ADD = 0,  // fx_pkg::shift_add_e code
    parameter bit RECOMPUTE_COSTS = 1'b0
);
  logic clk = 1'b0;
  logic rst = 1'b1;
  initial forever #5 clk = !clk;

`include "tb_cfg_signals.svh"
  logic [fx_pkg::STATUS_BITS-1:0] status;
  logic [fx_pkg::IN_BEAT_BITS-1:0] s_axis_tdata;
  logic s_axis_tvalid, s_axis_tready, s_axis_tlast, s_axis_tuser;
  fx_pkg::out_beat_t m_axis_tdata;
  logic m_axis_tvalid, m_axis_tready, m_axis_tlast, m_axis_tuser;
  logic done;
  int errors, frames, stall_cycles;

  stereo_top #(
      .WIDTH(WIDTH), .HEIGHT(HEIGHT), .NDISP(NDISP), .WINDOW(WINDOW),
      .RUNTIME_KERNEL(RUNTIME_KERNEL), .MAX_MIN_DISP(MAX_MIN_DISP),
      .COST(fx_pkg::cost_e'(COST)), .LANES(LANES),
      .SHIFT_ADD(fx_pkg::shift_add_e'(SHIFT_ADD)), .RECOMPUTE_COSTS(RECOMPUTE_COSTS)
  ) dut (
      .*
  );

  tb_stereo_vectors #(
      .WIDTH(WIDTH), .HEIGHT(HEIGHT), .NDISP(NDISP), .WINDOW(WINDOW),
      .RUNTIME_KERNEL(RUNTIME_KERNEL), .MAX_MIN_DISP(MAX_MIN_DISP), .COST(COST), .LANES(LANES)
  ) vectors (
      .go(!rst),
      .m_axis_tdata(m_axis_tdata),
      .*
  );

  initial begin
    repeat (4) @(negedge clk);
    rst = 1'b0;  // between edges: no race with the clocked processes
    wait (done);
    if (status != '0) begin
      $display("tb_stereo_top: FAIL: status = %b (sticky: 0 tlast, 1 tuser, 2 clamped)", status);
      $fatal(1, "tb_stereo_top: status");
    end
    if (errors != 0) begin
      $display("tb_stereo_top: FAIL: %0d errors", errors);
      $fatal(1, "tb_stereo_top: %0d errors", errors);
    end
    $display("tb_stereo_top: PASS: %0d frame(s) of %0dx%0d, every output beat equal, %0d stall cycles",
             frames, cfg_width, cfg_height, stall_cycles);
    $finish;
  end
endmodule

`default_nettype wire
