# docs/img/paper001-bracket.svg from the runs of docs/validation.md, paper 001, made in the
# directory holding their recording directories (empty, b50s1, b70s1, b90s1, pb70s1):
#   gnuplot paper001-bracket.gp
set terminal svg size 900,380 font "sans,12" background "white"
set output "paper001-bracket.svg"
set datafile separator ","
set xlabel "frequency [Hz]"
set xrange [224:242]
set grid
set key left top
# Columns of points.csv: 3 frequency_hz, 7-8 base_acc (re, im), 10-11 acc_sensor (Z),
# 13-14 acc_sensor_y (Y); the transmissibility is the sensor's over the table's amplitude.
tf(re, im) = sqrt(column(re)**2 + column(im)**2) / sqrt(column(7)**2 + column(8)**2)
points(c) = c . "/points.csv"
set multiplot layout 1,2 title "Paper 001 bracket, 8.1 g along Z, four B-dampers of 2 mm tungsten carbide"
set ylabel "transmissibility Y, sensor / table"
set yrange [0:17]
plot points("empty") every ::1 u 3:(tf(13, 14)) smooth unique w l lw 2 lc rgb "black" t "0 % (empty)", \
     points("b50s1") every ::1 u 3:(tf(13, 14)) smooth unique w lp pt 7 ps 0.5 lc rgb "#2ca02c" t "50 %", \
     points("b70s1") every ::1 u 3:(tf(13, 14)) smooth unique w lp pt 7 ps 0.5 lc rgb "#1f77b4" t "70 %", \
     points("b90s1") every ::1 u 3:(tf(13, 14)) smooth unique w lp pt 7 ps 0.5 lc rgb "#d62728" t "90 %", \
     points("pb70s1") every ::1 u 3:(tf(13, 14)) smooth unique w lp pt 6 ps 0.5 dt 2 lc rgb "#9467bd" t "70 % lead"
set ylabel "transmissibility Z, sensor / table"
set yrange [0:7]
unset key
plot points("empty") every ::1 u 3:(tf(10, 11)) smooth unique w l lw 2 lc rgb "black", \
     points("b50s1") every ::1 u 3:(tf(10, 11)) smooth unique w lp pt 7 ps 0.5 lc rgb "#2ca02c", \
     points("b70s1") every ::1 u 3:(tf(10, 11)) smooth unique w lp pt 7 ps 0.5 lc rgb "#1f77b4", \
     points("b90s1") every ::1 u 3:(tf(10, 11)) smooth unique w lp pt 7 ps 0.5 lc rgb "#d62728", \
     points("pb70s1") every ::1 u 3:(tf(10, 11)) smooth unique w lp pt 6 ps 0.5 dt 2 lc rgb "#9467bd"
unset multiplot
