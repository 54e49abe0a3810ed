# Constraints of stereo_arty_top (rtl/stereo_arty_top.sv) on a Digilent Arty A7-35T or A7-100T:
# every port of the module, with the pins of the board's reference manual and master XDC. The
# ctest board.arty_xdc_constrains_every_port compares the ports named here with the module's.

# 100 MHz oscillator (CLK100MHZ).
set_property -dict {PACKAGE_PIN E3 IOSTANDARD LVCMOS33} [get_ports clk]
create_clock -name sys_clk -period 10.000 -waveform {0.000 5.000} [get_ports clk]

# USB-UART of the FTDI chip: uart_txd_in (host to FPGA), uart_rxd_out (FPGA to host).
set_property -dict {PACKAGE_PIN A9 IOSTANDARD LVCMOS33} [get_ports uart_rx]
set_property -dict {PACKAGE_PIN D10 IOSTANDARD LVCMOS33} [get_ports uart_tx]

# RESET button (ck_rst), active low; synchronised by the power-on reset logic.
set_property -dict {PACKAGE_PIN C2 IOSTANDARD LVCMOS33} [get_ports button_n]

# Green LEDs LD4 .. LD7.
set_property -dict {PACKAGE_PIN H5 IOSTANDARD LVCMOS33} [get_ports {led[0]}]
set_property -dict {PACKAGE_PIN J5 IOSTANDARD LVCMOS33} [get_ports {led[1]}]
set_property -dict {PACKAGE_PIN T9 IOSTANDARD LVCMOS33} [get_ports {led[2]}]
set_property -dict {PACKAGE_PIN T10 IOSTANDARD LVCMOS33} [get_ports {led[3]}]

# The UART, the button and the LEDs are asynchronous to the clock.
set_false_path -from [get_ports {uart_rx button_n}]
set_false_path -to [get_ports {uart_tx led[*]}]

set_property CFGBVS VCCO [current_design]
set_property CONFIG_VOLTAGE 3.3 [current_design]
