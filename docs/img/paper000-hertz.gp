# docs/img/paper000-hertz.svg: the horizontal arrangements of paper 000 with the default linear
# contact (the nine-level run of docs/validation.md, recording directory `out`) and with the
# Hertz law of the enclosure's materials (recording directory `hertz`), made in the directory
# holding both:
#   gnuplot paper000-hertz.gp
set terminal svg size 1200,420 font "sans,12" background "white"
set output "paper000-hertz.svg"
set datafile separator ","
set multiplot layout 1,3 title "Paper 000, horizontal oscillation: damping against the RMS level, linear contact and Hertz of steel on aluminium ends and a PMMA tube (one filling)"
set xlabel "level [g RMS]"
set ylabel "damping ratio [%]"
set xrange [0:5.2]
set yrange [0:5]
set grid
set key top right
# damping.csv: arrangement, level_g, natural_frequency_hz, damping_ratio, method, ...
rows(dir, a, m) = sprintf("< awk -F, '$1 == \"%s\" && $5 == \"%s\"' %s/damping.csv | sort -t, -k2,2g", a, m, dir)
# where paper 000's experiment damps less than its simulation: 0.75 g with the axis along the
# motion, 1 g across it
mismatch(a) = a eq "H-0" ? 0.75 : 1.0
do for [a in "H-0 H-45 H-90"] {
    set title a
    set arrow 1 from mismatch(a), graph 0 to mismatch(a), graph 1 nohead dt 2 lc rgb "#7f7f7f"
    set label 1 "paper: experiment\nbelow simulation" at mismatch(a), graph 0.12 offset 0.5,0 font ",10" tc rgb "#7f7f7f"
    if (a eq "H-0") { set key top right } else { unset key }
    plot rows("out", a, "circle-fit") u 2:(100 * $4) w lp lw 2 pt 7 lc rgb "#1f77b4" t "linear (default), circle fit", \
         rows("out", a, "half-power") u 2:(100 * $4) w p pt 6 ps 1.2 lc rgb "#1f77b4" t "half-power (open)", \
         rows("hertz", a, "circle-fit") u 2:(100 * $4) w lp lw 2 pt 5 lc rgb "#d62728" t "Hertz, Al ends, PMMA tube", \
         rows("hertz", a, "half-power") u 2:(100 * $4) w p pt 4 ps 1.2 lc rgb "#d62728" notitle
}
unset multiplot
