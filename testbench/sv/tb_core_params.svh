// The parameters of the core under test that every top-level testbench and tb_stereo_vectors
// share: stereo_top's, as plain codes so that any simulator's -G/-g sets them. Included at the
// head of a parameter list; the includer adds its own after it.
    parameter int WIDTH = 64,
    parameter int HEIGHT = 48,
    parameter int NDISP = 16,
    parameter int WINDOW = 5,
    parameter bit RUNTIME_KERNEL = 1'b1,
    parameter int MAX_MIN_DISP = fx_pkg::DEFAULT_MAX_MIN_DISP,
    parameter int COST = 0,  // fx_pkg::cost_e code: 0 AD, 1 LCDM, 2 census
    parameter int LANES = NDISP,
