# docs/img/paper002-energy.svg from the two characterisations of docs/validation.md, paper 002
# (where the energy goes), made in the directory holding their output directories nogrid and
# grid:
#   gnuplot paper002-energy.gp
set terminal svg size 900,380 font "sans,12" background "white"
set output "paper002-energy.svg"
set datafile separator ","
set multiplot layout 1,2
# Left: the dissipated power per 5 mm layer, mean over the fillings (columns 13-22 of
# characterization_energy.csv: layer_1_w ... layer_10_w).
set print $layers
do for [l=1:10] {
    stats "nogrid/characterization_energy.csv" u (column(12 + l)) nooutput
    without = STATS_mean * 1e3
    stats "grid/characterization_energy.csv" u (column(12 + l)) nooutput
    print sprintf("%d,%g,%g", l, without, STATS_mean * 1e3)
}
unset print
set title "Dissipated power per layer (10.5 g, 120 Hz)"
set xlabel "dissipated power [mW]"
set ylabel "layer, 5 mm each, from the bottom"
set yrange [0.5:10.5]
set ytics 1
set xrange [0:*]
set grid
set key top right
plot $layers u 2:1 w lp pt 7 lw 2 lc rgb "#1f77b4" t "no grid", \
     $layers u 3:1 w lp pt 5 lw 2 lc rgb "#d62728" t "grid"
# Right: the laboratory kinetic energy's spectrum, first filling (columns of
# energy_spectrum.csv: seed 5, bin_hz 6, kinetic_lab_j 7).
set title "Spectrum of the bed's kinetic energy, filling 1"
set xlabel "frequency [Hz]"
set ylabel "amplitude [mJ]"
set xrange [0:500]
set yrange [0:*]
set xtics 40
set ytics auto
set key top right
plot "nogrid/energy_spectrum.csv" u ($6 - 1):($5 == 1 ? $7 * 1e3 : 1/0) w impulses lw 3 lc rgb "#1f77b4" t "no grid", \
     "grid/energy_spectrum.csv" u ($6 + 1):($5 == 1 ? $7 * 1e3 : 1/0) w impulses lw 3 lc rgb "#d62728" t "grid"
unset multiplot
