// tb_stereo_axil_top: the self-checking SystemVerilog testbench of stereo_axil_top (README.md).
// An AXI4-Lite master reads ID and VERSION, writes the frame configuration into the registers
// (FRAME, MATCH, STAGE6, THRESHOLDS and, with RUNTIME_KERNEL = 1, KERNEL[i]; address and data
// with random, independent delays) and reads each back; then tb_stereo_vectors streams the
// vectors with random gaps and stalls and compares every output beat; at the end STATUS must be
// 0, FRAMES_IN and FRAMES_OUT the frame count, and STALLS the stall cycles the testbench counted.
// Ends with "tb_stereo_axil_top: PASS ..." and $finish, or "... FAIL ..." and $fatal.
`default_nettype none

module tb_stereo_axil_top #(
    `include "tb_core_params.svh"
    parameter int SHIFT_ADD = 0,  // fx_pkg::shift_add_e code
    parameter bit RECOMPUTE_COSTS = 1'b0,
    parameter int ADDR_BITS = 8
);
  logic clk = 1'b0;
  logic rst = 1'b1;
  initial forever #5 clk = !clk;

  logic [ADDR_BITS-1:0] s_axil_awaddr, s_axil_araddr;
  logic s_axil_awvalid, s_axil_awready, s_axil_wvalid, s_axil_wready, s_axil_bvalid, s_axil_bready;
  logic s_axil_arvalid, s_axil_arready, s_axil_rvalid, s_axil_rready;
  logic [31:0] s_axil_wdata, s_axil_rdata;
  logic [3:0] s_axil_wstrb;
  logic [1:0] s_axil_bresp, s_axil_rresp;
  logic [fx_pkg::IN_BEAT_BITS-1:0] s_axis_tdata;
  logic s_axis_tvalid, s_axis_tready, s_axis_tlast, s_axis_tuser;
  fx_pkg::out_beat_t m_axis_tdata;
  logic m_axis_tvalid, m_axis_tready, m_axis_tlast, m_axis_tuser;

`include "tb_cfg_signals.svh"
  logic go, done;
  int errors, frames, stall_cycles;

  stereo_axil_top #(
      .WIDTH(WIDTH), .HEIGHT(HEIGHT), .NDISP(NDISP), .WINDOW(WINDOW),
      .RUNTIME_KERNEL(RUNTIME_KERNEL), .MAX_MIN_DISP(MAX_MIN_DISP),
      .COST(fx_pkg::cost_e'(COST)), .LANES(LANES),
      .SHIFT_ADD(fx_pkg::shift_add_e'(SHIFT_ADD)), .RECOMPUTE_COSTS(RECOMPUTE_COSTS),
      .ADDR_BITS(ADDR_BITS)
  ) dut (
      .*
  );

  tb_stereo_vectors #(
      .WIDTH(WIDTH), .HEIGHT(HEIGHT), .NDISP(NDISP), .WINDOW(WINDOW),
      .RUNTIME_KERNEL(RUNTIME_KERNEL), .MAX_MIN_DISP(MAX_MIN_DISP), .COST(COST), .LANES(LANES)
  ) vectors (
      .m_axis_tdata(m_axis_tdata),
      .*
  );

  // ---- AXI4-Lite master: one transaction at a time, random delays --------------------------
  logic [31:0] rng = 32'h2545F491;
`include "tb_xorshift.svh"
  // 0 .. 3 clock edges, from the testbench's own generator.
  task automatic random_wait();
    rng = xorshift(rng);
    repeat (rng % 4) @(negedge clk);
  endtask

  task automatic fail(input string message);
    $display("tb_stereo_axil_top: FAIL: %s", message);
    $fatal(1, "tb_stereo_axil_top: %s", message);
  endtask

  // The write address and data are offered with independent random delays (either may come
  // first); both stay until taken. Signals change between clock edges (negedge).
  task automatic axil_write(input int offset, input logic [31:0] data);
    fork
      begin
        random_wait();
        s_axil_awaddr = ADDR_BITS'(offset);
        s_axil_awvalid = 1'b1;
        do @(posedge clk); while (!s_axil_awready);
        @(negedge clk) s_axil_awvalid = 1'b0;
      end
      begin
        random_wait();
        s_axil_wdata = data;
        s_axil_wstrb = 4'hF;
        s_axil_wvalid = 1'b1;
        do @(posedge clk); while (!s_axil_wready);
        @(negedge clk) s_axil_wvalid = 1'b0;
      end
    join
    s_axil_bready = 1'b1;
    do @(posedge clk); while (!s_axil_bvalid);
    if (s_axil_bresp != 2'b00) fail($sformatf("write of 0x%02h: response %0d", offset, s_axil_bresp));
    @(negedge clk) s_axil_bready = 1'b0;
  endtask

  task automatic axil_read(input int offset, output logic [31:0] data);
    random_wait();
    s_axil_araddr = ADDR_BITS'(offset);
    s_axil_arvalid = 1'b1;
    do @(posedge clk); while (!s_axil_arready);
    @(negedge clk) s_axil_arvalid = 1'b0;
    s_axil_rready = 1'b1;
    do @(posedge clk); while (!s_axil_rvalid);
    data = s_axil_rdata;
    if (s_axil_rresp != 2'b00) fail($sformatf("read of 0x%02h: response %0d", offset, s_axil_rresp));
    @(negedge clk) s_axil_rready = 1'b0;
  endtask

  // Writes a register and reads it back.
  task automatic write_checked(input int offset, input logic [31:0] data);
    logic [31:0] back;
    axil_write(offset, data);
    axil_read(offset, back);
    if (back != data) fail($sformatf("register 0x%02h reads 0x%08h after writing 0x%08h", offset,
                                     back, data));
  endtask

  // Reads a register that must hold `expected`.
  task automatic expect_register(input int offset, input logic [31:0] expected, input string name);
    logic [31:0] value;
    axil_read(offset, value);
    if (value != expected) fail($sformatf("%s = 0x%08h, expected 0x%08h", name, value, expected));
  endtask

  initial begin
    s_axil_awvalid = 1'b0;
    s_axil_wvalid = 1'b0;
    s_axil_bready = 1'b0;
    s_axil_arvalid = 1'b0;
    s_axil_rready = 1'b0;
    s_axil_awaddr = '0;
    s_axil_araddr = '0;
    s_axil_wdata = '0;
    s_axil_wstrb = '0;
    go = 1'b0;
    repeat (4) @(negedge clk);
    rst = 1'b0;
    expect_register('h00, fx_pkg::REGMAP_ID, "ID");
    expect_register('h04, fx_pkg::REGMAP_VERSION, "VERSION");
    write_checked('h10, {cfg_height, cfg_width});
    write_checked('h14, {7'b0, cfg_use_ca, 3'b0, cfg_radius, 7'b0, cfg_ndisp});
    write_checked('h18, {17'b0, cfg_subpixel_en, cfg_lr_en, cfg_uniqueness_en, cfg_min_disp});
    write_checked('h1C, {16'b0, cfg_lr_tolerance, cfg_uniqueness});
    if (RUNTIME_KERNEL) begin
      for (int i = 0; i < WINDOW; i++) begin
        write_checked('h40 + 4 * i, 32'(cfg_kernel[i*fx_pkg::TAP_BITS+:fx_pkg::TAP_BITS]));
      end
    end
    @(negedge clk) go = 1'b1;
    wait (done);
    expect_register('h20, 32'd0, "STATUS");
    expect_register('h28, 32'(frames), "FRAMES_IN");
    expect_register('h2C, 32'(frames), "FRAMES_OUT");
    expect_register('h30, 32'(stall_cycles), "STALLS");
    if (errors != 0) fail($sformatf("%0d errors", errors));
    $display("tb_stereo_axil_top: PASS: %0d frame(s) of %0dx%0d, every output beat equal, registers as expected, %0d stall cycles",
             frames, cfg_width, cfg_height, stall_cycles);
    $finish;
  end
endmodule

`default_nettype wire
