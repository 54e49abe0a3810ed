// stereo_lcdm_convert: one RGB pixel to its point (a, b) = 512 S (cos H, sin H) on the HSL
// hue-saturation disc of the LCDM cost (model: stereo::lcdm::chroma, docs/fixed-point.md
// "LCDM"). Combinational: two dividers (saturation, hue index) and the quarter-wave cosine
// table of fx_pkg, read twice (cos and sin). A grey pixel (C = 0) is the centre (0, 0).
`default_nettype none

module stereo_lcdm_convert (
    input  wire logic        [fx_pkg::RGB_BITS-1:0]        in_rgb,  // {R, G, B}
    output      logic signed [fx_pkg::LCDM_COORD_BITS-1:0] out_a,
    output      logic signed [fx_pkg::LCDM_COORD_BITS-1:0] out_b
);
  localparam int TRIG_BITS = fx_pkg::LCDM_TRIG_BITS;
  localparam int COORD_BITS = fx_pkg::LCDM_COORD_BITS;
  localparam int QUARTER = fx_pkg::LCDM_HUE_QUARTER;
  localparam int HUE_COUNT = fx_pkg::LCDM_HUE_COUNT;
  localparam int PRODUCT_BITS = 24;  // s * table entry: |.| <= 512 * 4096 = 2^21, plus rounding

  // cos(2 pi h / HUE_COUNT) from the quarter wave, by the symmetries of the cosine.
  function automatic logic signed [TRIG_BITS+1:0] cosine(input logic [10:0] h);
    if (h <= 11'(QUARTER)) cosine = fx_pkg::lcdm_quarter_cos(9'(h));
    else if (h <= 11'(2 * QUARTER)) cosine = -fx_pkg::lcdm_quarter_cos(9'(11'(2 * QUARTER) - h));
    else if (h <= 11'(3 * QUARTER)) cosine = -fx_pkg::lcdm_quarter_cos(9'(h - 11'(2 * QUARTER)));
    else cosine = fx_pkg::lcdm_quarter_cos(9'(11'(HUE_COUNT) - h));
  endfunction

  // (s * entry + 2^(TRIG_BITS-1)) >>> TRIG_BITS: the rounded coordinate.
  function automatic logic signed [COORD_BITS-1:0] scale(input logic [9:0] s,
                                                         input logic signed [TRIG_BITS+1:0] entry);
    logic signed [PRODUCT_BITS-1:0] product;
    /* verilator lint_off UNUSEDSIGNAL */  // the coordinate is the low bits of the shifted sum
    logic signed [PRODUCT_BITS-1:0] shifted;
    /* verilator lint_on UNUSEDSIGNAL */
    product = $signed({{(PRODUCT_BITS - 10) {1'b0}}, s}) *
              $signed({{(PRODUCT_BITS - TRIG_BITS - 2) {entry[TRIG_BITS+1]}}, entry});
    shifted = (product + PRODUCT_BITS'(1 << (TRIG_BITS - 1))) >>> TRIG_BITS;
    scale = shifted[COORD_BITS-1:0];
  endfunction

  logic [7:0] r, g, b, mx, mn, c;
  logic [8:0] l2, dark_side, light_side, den;
  logic [18:0] s_num;  // 2 C 512 + den <= 261375
  /* verilator lint_off UNUSEDSIGNAL */  // the high bits are zero: s <= 512, h <= 1536
  logic [18:0] s_quotient;
  logic [19:0] h_quotient;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [10:0] t;                  // hexagonal hue times C, 0 .. 6C
  logic [19:0] h_num;  // 512 t + C <= 783615
  logic [10:0] h, h_sin;

  always_comb begin
    r = in_rgb[23:16];
    g = in_rgb[15:8];
    b = in_rgb[7:0];
    mx = (r >= g) ? ((r >= b) ? r : b) : ((g >= b) ? g : b);
    mn = (r <= g) ? ((r <= b) ? r : b) : ((g <= b) ? g : b);
    c = mx - mn;
    l2 = {1'b0, mx} + {1'b0, mn};
    light_side = 9'(fx_pkg::LCDM_LIGHT_SUM) - l2;
    dark_side = (l2 < light_side) ? l2 : light_side;
    den = (dark_side > 9'(fx_pkg::LCDM_DARK_FLOOR)) ? dark_side : 9'(fx_pkg::LCDM_DARK_FLOOR);
    s_num = {1'b0, c, 10'b0} + {10'b0, den};  // 2 C 2^9 + den
    s_quotient = s_num / {9'b0, den, 1'b0};
    // Modulo 2^11: the result lies in 0 .. 6C, intermediate wraps cancel.
    if (mx == r) t = (g >= b) ? 11'(g) - 11'(b) : 11'(6) * 11'(c) + 11'(g) - 11'(b);
    else if (mx == g) t = 11'(2) * 11'(c) + 11'(b) - 11'(r);
    else t = 11'(4) * 11'(c) + 11'(r) - 11'(g);
    h_num = {t, 9'b0} + {12'b0, c};  // 2 * 256 * t + C
    h_quotient = h_num / ((c == 8'd0) ? 20'd1 : {11'b0, c, 1'b0});
    h = (h_quotient[10:0] == 11'(HUE_COUNT)) ? '0 : h_quotient[10:0];
    h_sin = (h >= 11'(QUARTER)) ? h - 11'(QUARTER) : h + 11'(3 * QUARTER);  // sin = cos(h + 3/4)
    if (c == 8'd0) begin
      out_a = '0;
      out_b = '0;
    end else begin
      out_a = scale(s_quotient[9:0], cosine(h));
      out_b = scale(s_quotient[9:0], cosine(h_sin));
    end
  end
endmodule

`default_nettype wire
