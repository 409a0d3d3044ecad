# docs/img/paper000-campaign.svg from the six-arrangement run of docs/validation.md, paper 000,
# made in the directory holding its recording directory `out`:
#   gnuplot paper000-campaign.gp
set terminal svg size 900,420 font "sans,12" background "white"
set output "paper000-campaign.svg"
set datafile separator ","
set multiplot layout 1,2 title "Paper 000: damping of the first mode against the RMS level at the damper (one filling)"
set xlabel "level [g RMS]"
set ylabel "damping ratio [%]"
set xrange [0:5.2]
set yrange [0:*]
set grid
set key top right
# damping.csv: arrangement, level_g, natural_frequency_hz, damping_ratio, method, ...
rows(a, m) = sprintf("< awk -F, '$1 == \"%s\" && $5 == \"%s\"' out/damping.csv | sort -t, -k2,2g", a, m)
colours = "#1f77b4 #2ca02c #d62728"
do for [side in "H V"] {
    set title (side eq "H" ? "horizontal oscillation" : "vertical oscillation")
    plot for [k = 1:3] rows(side . "-" . word("0 45 90", k), "circle-fit") u 2:(100 * $4) \
             w lp lw 2 pt 7 lc rgb word(colours, k) t side . "-" . word("0 45 90", k) . " circle fit", \
         for [k = 1:3] rows(side . "-" . word("0 45 90", k), "half-power") u 2:(100 * $4) \
             w p pt 6 ps 1.2 lc rgb word(colours, k) t (k == 1 ? "half-power (open)" : "")
}
unset multiplot
