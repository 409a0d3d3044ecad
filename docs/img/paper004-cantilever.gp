# docs/img/paper004-cantilever.svg from the four runs of docs/validation.md, paper 004 (the
# coupled cantilever), made in the directory holding their recording directories case1-case4:
#   gnuplot paper004-cantilever.gp
set terminal svg size 760,400 font "sans,12" background "white"
set output "paper004-cantilever.svg"
set datafile separator ","
set title "Paper 004 cantilever, 120 granules held, a share freed at 5 s"
set xlabel "time [s]"
set ylabel "tip displacement, half peak-to-peak per period [m]"
set xrange [0:15]
set yrange [0:0.25]
set grid
set key outside right top
set arrow from 5,0 to 5,0.25 nohead dt 2 lc rgb "gray40"
# Columns of transient/V_0.01m_envelope.csv: period, start_s, then the minimum and the
# maximum of every channel (base_acc, acc_tip, tip, force_empid).
half(i) = (column(i + 4) - column(i)) / 2.0
envelope(c) = c . "/transient/V_0.01m_envelope.csv"
plot envelope("case1") every ::1 u 2:(half(5)) w l lw 2 lc rgb "#1f77b4" t "1: all held", \
     envelope("case2") every ::1 u 2:(half(5)) w l lw 2 lc rgb "#2ca02c" t "2: 30 % freed", \
     envelope("case3") every ::1 u 2:(half(5)) w l lw 2 lc rgb "#ff7f0e" t "3: 60 % freed", \
     envelope("case4") every ::1 u 2:(half(5)) w l lw 2 lc rgb "#d62728" t "4: all freed", \
     0.22 w l dt 3 lw 2 lc rgb "#1f77b4" t "paper: 0.22 m held", \
     0.05 w l dt 3 lw 2 lc rgb "#ff7f0e" t "paper: 0.05 m (60 %)", \
     0.03 w l dt 3 lw 2 lc rgb "#d62728" t "paper: 0.03 m (all)"
